#pragma once

#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::sim {

// `count` start poses for a fleet on one terrain: the first is `first`, each next one the free
// cell farthest from those already chosen among cells at least `clearance` metres from any
// non-free cell (farthest-point sampling), so robots start spread out. Deterministic.
// Errors (kInvalidArgument): count < 1, or no cell with that clearance.
StatusOr<std::vector<Pose2>> SpreadStarts(const grid::OccupancyGrid& truth, const Pose2& first,
                                          int count, double clearance = 0.5);

}  // namespace fleetmap::sim
