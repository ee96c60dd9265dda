#pragma once

// The judge of a route graph's clearance: the exact distance to the nearest cell that is not
// free, by brute force over the cells around a point, sharing no code with the builder's
// ClearanceMap (common/route_graph/clearance_map.hpp), so a bug there cannot hide here.
// `bench route-graph` and the route graph's tests judge with it. Any thread.

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

// The distance from `point` to the nearest cell that is not free (or to the grid's outside),
// looking `reach` metres around; `reach` when nothing blocked is nearer.
double ExactClearance(const grid::OccupancyGrid& grid, const Point2& point, double reach);

// The smallest ExactClearance along the segment a-b, sampled every eighth of a cell.
double SegmentExactClearance(const grid::OccupancyGrid& grid, const Point2& a, const Point2& b,
                             double reach);

}  // namespace fleetmap::bench
