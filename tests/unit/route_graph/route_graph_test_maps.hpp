#pragma once

// Synthetic floor plans with a known topology for the route graph's tests, and an independent
// judge of clearance: the exact distance from a point to the nearest blocked cell's square,
// computed by brute force (it shares no code with ClearanceMap).

#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/route_graph/clearance_judge.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::route_graph::testing {

// A grid of `width_m` x `height_m` metres at `resolution`, all occupied.
inline grid::OccupancyGrid SolidGrid(double width_m, double height_m, double resolution = 0.05) {
  return grid::OccupancyGrid(static_cast<int>(std::lround(width_m / resolution)),
                             static_cast<int>(std::lround(height_m / resolution)), resolution,
                             Pose2{}, grid::kOccupiedValue);
}

// Sets the cells whose centres lie in [x0, x1) x [y0, y1) metres to `value`.
inline void Fill(grid::OccupancyGrid* grid, double x0, double y0, double x1, double y1,
                 int8_t value = grid::kFreeValue) {
  for (int y = 0; y < grid->height(); ++y) {
    for (int x = 0; x < grid->width(); ++x) {
      const Point2 centre = grid->CellCenter(x, y);
      if (centre.x() >= x0 && centre.x() < x1 && centre.y() >= y0 && centre.y() < y1) {
        grid->at(x, y) = value;
      }
    }
  }
}

// The judge of clearance (bench/route_graph/clearance_judge.hpp), shared with the benchmark.
using bench::ExactClearance;
using bench::SegmentExactClearance;

// Two 6 x 6 m rooms side by side, the wall between them 0.2 m thick with a door `door` m wide,
// in a 14 x 8 m grid; free: x in [1, 7) and [7.2, 13.2), y in [1, 7); door centred on y = 4.
inline grid::OccupancyGrid TwoRooms(double door) {
  grid::OccupancyGrid grid = SolidGrid(14.2, 8.0);
  Fill(&grid, 1.0, 1.0, 7.0, 7.0);
  Fill(&grid, 7.2, 1.0, 13.2, 7.0);
  Fill(&grid, 7.0, 4.0 - door / 2, 7.2, 4.0 + door / 2);
  return grid;
}

}  // namespace fleetmap::route_graph::testing
