#include "bench/bytes/tile_bytes_comparison.hpp"

#include "common/core/check.hpp"

namespace fleetmap::bench {
namespace {

double RatioOf(size_t vector, size_t baseline) {
  return baseline > 0 ? static_cast<double>(vector) / static_cast<double>(baseline) : 0.0;
}

}  // namespace

TileBytesComparison& TileBytesComparison::operator+=(const TileBytesComparison& other) {
  grid.tiles += other.grid.tiles;
  grid.bytes += other.grid.bytes;
  vector.tiles += other.vector.tiles;
  vector.payload += other.vector.payload;
  return *this;
}

std::vector<NamedRatio> TileBytesComparison::Ratios() const {
  std::vector<NamedRatio> ratios;
  for (const NamedBytes& baseline : TileBaselines(grid.bytes)) {
    ratios.push_back({baseline.name, RatioOf(vector.payload, baseline.bytes)});
  }
  return ratios;
}

NamedRatio TileBytesComparison::RatioToSmallest() const {
  const NamedBytes smallest = SmallestTileBaseline(grid.bytes);
  return {smallest.name, RatioOf(vector.payload, smallest.bytes)};
}

double TileBytesComparison::RatioTo(size_t GridTileBytes::*baseline) const {
  return RatioOf(vector.payload, grid.bytes.*baseline);
}

std::vector<std::string> TileBaselineNames(bool with_dictionary) {
  GridTileBytes measured;
  measured.zstd19_dict = with_dictionary ? 1 : 0;
  std::vector<std::string> names;
  for (const NamedBytes& baseline : TileBaselines(measured)) names.push_back(baseline.name);
  return names;
}

TileBytesHeadline HeadlineOf(const std::vector<NamedComparison>& maps) {
  FLEETMAP_CHECK(!maps.empty(), "a headline needs at least one map");
  TileBytesComparison total;
  TileBytesHeadline headline;
  bool first = true;
  for (const NamedComparison& map : maps) {
    total += map.bytes;
    const NamedRatio ratio = map.bytes.RatioToSmallest();
    if (first || ratio.ratio > headline.worst.ratio) {
      headline.worst = ratio;
      headline.worst_map = map.name;
      first = false;
    }
  }
  headline.summed = total.RatioToSmallest();
  return headline;
}

}  // namespace fleetmap::bench
