#pragma once

// Terrain -> ground-truth occupancy grid. The grid covers the terrain's square exactly (origin
// (0, 0), ceil(size / resolution) cells a side). Occupied (100): cells whose centre lies inside a
// solid polygon, within thickness / 2 of a wall's segment (or of a closed door's), or in the cell a
// wall's centre line crosses (so a wall thinner than a cell still closes); free (0): every other
// cell. There is no unknown: the boundary wall runs along the edge of the square, and the inside of
// an obstacle is occupied (it is an obstacle, even if no laser ever sees it).
//
// Thread-safety: stateless.

#include <cstdint>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

// A larger ground truth is refused (8000 x 8000 cells: 400 m at 5 cm).
inline constexpr int64_t kMaxGroundTruthCells = 64'000'000;

// Errors (kInvalidArgument): resolution <= 0 or not finite; more than kMaxGroundTruthCells cells.
StatusOr<grid::OccupancyGrid> RasterizeTerrain(const Terrain& terrain, double resolution);

}  // namespace fleetmap::sim
