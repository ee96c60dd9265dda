#pragma once

// `fleetmap sim --shards K`: the sharded fleet's rt/fleetmap/map (the aggregator's join of the
// shards' grids) against the grid of a reference server that fused every region in the same run.
// Fusion is per tile, so the two should agree cell for cell; cells that differ are counted apart
// where they lie within one tile of a border between shards (where a robot's map is cut between
// two servers) and elsewhere.

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct ShardComparison {
  int64_t cells = 0;  // compared: the union of both grids' extents
  int64_t differing = 0;
  int64_t differing_near_border = 0;
  int64_t known_sharded = 0;  // known cells in each grid
  int64_t known_reference = 0;

  std::string Markdown(int shards) const;
};

// Both grids must lie on one cell lattice (the fleet's fusion resolution); an empty grid compares
// as all unknown.
StatusOr<ShardComparison> CompareShardedMap(const grid::OccupancyGrid& sharded,
                                            const grid::OccupancyGrid& reference,
                                            const std::vector<ShardRegion>& regions,
                                            double tile_size);

}  // namespace fleetmap::bench
