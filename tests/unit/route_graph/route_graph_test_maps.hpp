#pragma once

// Synthetic floor plans with a known topology for the route graph's tests, and an independent
// judge of clearance: the exact distance from a point to the nearest blocked cell's square,
// computed by brute force (it shares no code with ClearanceMap).

#include <algorithm>
#include <cmath>
#include <limits>

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

// The distance from `point` to the nearest cell that is not free (or to the grid's outside),
// looking `reach` metres around; `reach` when nothing blocked is nearer.
inline double ExactClearance(const grid::OccupancyGrid& grid, const Point2& point, double reach) {
  const double resolution = grid.resolution();
  const Point2 local = point - Point2(grid.origin().x, grid.origin().y);
  const int cx = static_cast<int>(std::floor(local.x() / resolution));
  const int cy = static_cast<int>(std::floor(local.y() / resolution));
  const int cells = static_cast<int>(std::ceil(reach / resolution)) + 1;
  double best = reach;
  for (int y = cy - cells; y <= cy + cells; ++y) {
    for (int x = cx - cells; x <= cx + cells; ++x) {
      const bool blocked = !grid.Contains(x, y) || grid.StateAt(x, y) != grid::CellState::kFree;
      if (!blocked) continue;
      const double dx =
          std::max({x * resolution - local.x(), 0.0, local.x() - (x + 1) * resolution});
      const double dy =
          std::max({y * resolution - local.y(), 0.0, local.y() - (y + 1) * resolution});
      best = std::min(best, std::hypot(dx, dy));
    }
  }
  return best;
}

// The smallest exact clearance along a segment, sampled every eighth of a cell.
inline double SegmentExactClearance(const grid::OccupancyGrid& grid, const Point2& a,
                                    const Point2& b, double reach) {
  const double step = grid.resolution() / 8.0;
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i) {
    lowest = std::min(lowest, ExactClearance(grid, a + (b - a) * (double(i) / steps), reach));
  }
  return lowest;
}

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
