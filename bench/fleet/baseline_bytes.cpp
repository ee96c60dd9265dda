#include "bench/fleet/baseline_bytes.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace fleetmap::bench {

std::vector<BaselineBytes> Baselines(const WireBaselines& measured) {
  return {
      {"whole OccupancyGrid per change", "whole_grids", measured.grid_bytes},
      {"OccupancyGridUpdate patches", "patches", measured.patch_bytes},
      {"OccupancyGridUpdate patches, zstd -3", "patches_zstd3", measured.zstd3_bytes},
      {"OccupancyGridUpdate patches, zstd -19", "patches_zstd19", measured.zstd19_bytes},
      {"OccupancyGridUpdate patches, LZ4", "patches_lz4", measured.lz4_bytes},
  };
}

BaselineBytes SmallestBaseline(const WireBaselines& measured) {
  const std::vector<BaselineBytes> all = Baselines(measured);
  return *std::min_element(all.begin(), all.end(),
                           [](const auto& a, const auto& b) { return a.bytes < b.bytes; });
}

std::string HeadlineRatio(uint64_t tile_bytes, const WireBaselines& measured) {
  if (measured.events == 0) return "no grid-wire baseline measured";
  if (measured.patches_pending > 0) {
    return fmt::format("baselines incomplete ({} patches were not measured)",
                       measured.patches_pending);
  }
  if (tile_bytes == 0) return "no tile bytes";
  const BaselineBytes smallest = SmallestBaseline(measured);
  const double ratio = static_cast<double>(smallest.bytes) / static_cast<double>(tile_bytes);
  return fmt::format("{:.1f}x {} bytes than the smallest baseline, {} ({} bytes)",
                     ratio >= 1.0 ? ratio : 1.0 / ratio, ratio >= 1.0 ? "fewer" : "more",
                     smallest.name, smallest.bytes);
}

std::string BytesAndRatio(uint64_t baseline_bytes, uint64_t tile_bytes) {
  if (tile_bytes == 0) return fmt::format("{}", baseline_bytes);
  return fmt::format("{} ({:.1f}x)", baseline_bytes,
                     static_cast<double>(baseline_bytes) / tile_bytes);
}

}  // namespace fleetmap::bench
