#include "bench/route_graph/clearance_judge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::bench {

double ExactClearance(const grid::OccupancyGrid& grid, const Point2& point, double reach) {
  const double resolution = grid.resolution();
  const Point2 local = point - Point2(grid.origin().x, grid.origin().y);
  const int cx = static_cast<int>(std::floor(local.x() / resolution));
  const int cy = static_cast<int>(std::floor(local.y() / resolution));
  const int cells = static_cast<int>(std::ceil(reach / resolution)) + 1;
  double best = reach;
  for (int y = cy - cells; y <= cy + cells; ++y) {
    for (int x = cx - cells; x <= cx + cells; ++x) {
      if (grid.Contains(x, y) && grid.StateAt(x, y) == grid::CellState::kFree) continue;
      const double dx =
          std::max({x * resolution - local.x(), 0.0, local.x() - (x + 1) * resolution});
      const double dy =
          std::max({y * resolution - local.y(), 0.0, local.y() - (y + 1) * resolution});
      best = std::min(best, std::hypot(dx, dy));
    }
  }
  return best;
}

double SegmentExactClearance(const grid::OccupancyGrid& grid, const Point2& a, const Point2& b,
                             double reach) {
  const double step = grid.resolution() / 8.0;
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i) {
    const Point2 point = a + (b - a) * (static_cast<double>(i) / steps);
    lowest = std::min(lowest, ExactClearance(grid, point, reach));
  }
  return lowest;
}

}  // namespace fleetmap::bench
