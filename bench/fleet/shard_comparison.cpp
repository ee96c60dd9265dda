#include "bench/fleet/shard_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::bench {
namespace {

constexpr double kFarAway = 1e4;  // metres: a region edge this far out borders no other shard

// The grid's origin in whole cells of `resolution`, if it lies on that lattice.
std::optional<std::pair<int64_t, int64_t>> LatticeOrigin(const grid::OccupancyGrid& grid,
                                                         double resolution) {
  const double x = grid.origin().x / resolution;
  const double y = grid.origin().y / resolution;
  if (std::abs(x - std::round(x)) > 1e-3 || std::abs(y - std::round(y)) > 1e-3) return std::nullopt;
  return std::make_pair(static_cast<int64_t>(std::llround(x)),
                        static_cast<int64_t>(std::llround(y)));
}

grid::CellState StateAt(const grid::OccupancyGrid& grid, std::pair<int64_t, int64_t> origin,
                        int64_t x, int64_t y) {
  const int64_t cx = x - origin.first;
  const int64_t cy = y - origin.second;
  if (grid.empty() || cx < 0 || cy < 0 || cx >= grid.width() || cy >= grid.height()) {
    return grid::CellState::kUnknown;
  }
  return grid.StateAt(static_cast<int>(cx), static_cast<int>(cy));
}

// Within `distance` of an edge of a region that borders another shard (not the far-out edges).
bool NearBorder(double x, double y, const std::vector<ShardRegion>& regions, double distance) {
  for (const ShardRegion& region : regions) {
    for (const double edge : {region.min_x, region.max_x}) {
      if (std::abs(edge) < kFarAway && std::abs(x - edge) <= distance) return true;
    }
    for (const double edge : {region.min_y, region.max_y}) {
      if (std::abs(edge) < kFarAway && std::abs(y - edge) <= distance) return true;
    }
  }
  return false;
}

}  // namespace

StatusOr<ShardComparison> CompareShardedMap(const grid::OccupancyGrid& sharded,
                                            const grid::OccupancyGrid& reference,
                                            const std::vector<ShardRegion>& regions,
                                            double tile_size) {
  ShardComparison comparison;
  if (sharded.empty() && reference.empty()) return comparison;
  const double resolution = sharded.empty() ? reference.resolution() : sharded.resolution();
  if (!sharded.empty() && !reference.empty() &&
      !grid::SameResolution(sharded.resolution(), reference.resolution())) {
    return InvalidArgumentError(fmt::format("the sharded map has {} m cells, the reference {} m",
                                            sharded.resolution(), reference.resolution()));
  }
  const auto a = LatticeOrigin(sharded, resolution);
  const auto b = LatticeOrigin(reference, resolution);
  if (!a || !b) return InvalidArgumentError("the two maps do not lie on one cell lattice");
  int64_t min_x = std::numeric_limits<int64_t>::max(), min_y = min_x;
  int64_t max_x = std::numeric_limits<int64_t>::min(), max_y = max_x;
  for (const auto& [grid, origin] : {std::pair(&sharded, *a), std::pair(&reference, *b)}) {
    if (grid->empty()) continue;
    min_x = std::min(min_x, origin.first);
    min_y = std::min(min_y, origin.second);
    max_x = std::max(max_x, origin.first + grid->width());
    max_y = std::max(max_y, origin.second + grid->height());
  }
  for (int64_t y = min_y; y < max_y; ++y) {
    for (int64_t x = min_x; x < max_x; ++x) {
      const grid::CellState s = StateAt(sharded, *a, x, y);
      const grid::CellState r = StateAt(reference, *b, x, y);
      ++comparison.cells;
      comparison.known_sharded += s != grid::CellState::kUnknown;
      comparison.known_reference += r != grid::CellState::kUnknown;
      if (s == r) continue;
      ++comparison.differing;
      const double px = (static_cast<double>(x) + 0.5) * resolution;
      const double py = (static_cast<double>(y) + 0.5) * resolution;
      comparison.differing_near_border += NearBorder(px, py, regions, tile_size);
    }
  }
  return comparison;
}

std::string ShardComparison::Markdown(int shards) const {
  return fmt::format(
      "## Shards\n\n{} shard servers, each fusing a strip of the terrain, and the aggregator "
      "joining their grids into rt/fleetmap/map, against a reference server that fused every "
      "region in the same run (docs/shards.md): {} cells compared, {} known in the sharded map and "
      "{} in the reference; **{} differ** ({} of them within one tile of a border between shards, "
      "{} elsewhere).\n\n",
      shards, cells, known_sharded, known_reference, differing, differing_near_border,
      differing - differing_near_border);
}

}  // namespace fleetmap::bench
