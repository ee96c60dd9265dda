#include "common/sim/frame_resample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::sim {

void ResampleRigid(const grid::OccupancyGrid& source, const Transform2& source_from_target,
                   grid::OccupancyGrid* target) {
  std::vector<int8_t>& out = target->mutable_data();
  std::fill(out.begin(), out.end(), grid::kUnknownValue);
  if (source.empty() || target->empty()) return;
  // Target cell (x, y) lands at source cell coordinates a + x * dx + y * dy (before the floor):
  // an affine map, so a row is walked by adding dx, never by a transform per cell.
  const Eigen::Affine2d source_cells_from_target_cells =
      Eigen::Scaling(1.0 / source.resolution()) *
      Eigen::Affine2d((source.origin().ToTransform().inverse() * source_from_target *
                       target->origin().ToTransform())
                          .matrix()) *
      Eigen::Scaling(target->resolution());
  const Point2 a = source_cells_from_target_cells * Point2(0.5, 0.5);
  const Vector2 dx = source_cells_from_target_cells.linear() * Vector2(1.0, 0.0);
  const Vector2 dy = source_cells_from_target_cells.linear() * Vector2(0.0, 1.0);
  const std::vector<int8_t>& in = source.data();
  const int width = source.width();
  const int height = source.height();
  for (int y = 0; y < target->height(); ++y) {
    Point2 p = a + y * dy;
    int8_t* row = out.data() + static_cast<size_t>(y) * target->width();
    for (int x = 0; x < target->width(); ++x, p += dx) {
      const double fx = std::floor(p.x());
      const double fy = std::floor(p.y());
      if (fx < 0.0 || fy < 0.0 || fx >= width || fy >= height) continue;
      row[x] = in[static_cast<size_t>(fy) * width + static_cast<size_t>(fx)];
    }
  }
}

grid::OccupancyGrid ResampleIntoFrame(const grid::OccupancyGrid& source,
                                      const Transform2& to_from_source) {
  if (source.empty()) return grid::OccupancyGrid(0, 0, source.resolution());
  const double r = source.resolution();
  const Transform2 to_from_grid = to_from_source * source.origin().ToTransform();
  Point2 low = Point2::Constant(std::numeric_limits<double>::infinity());
  Point2 high = -low;
  for (const Point2& corner :
       {Point2(0.0, 0.0), Point2(source.width() * r, 0.0), Point2(0.0, source.height() * r),
        Point2(source.width() * r, source.height() * r)}) {
    const Point2 p = to_from_grid * corner;
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  // Corners that land on the lattice up to rounding stay on it (a quarter turn adds no cell).
  constexpr double kSlack = 1e-6;
  const double x0 = std::floor(low.x() / r + kSlack);
  const double y0 = std::floor(low.y() / r + kSlack);
  const int width = static_cast<int>(std::ceil(high.x() / r - kSlack) - x0);
  const int height = static_cast<int>(std::ceil(high.y() / r - kSlack) - y0);
  grid::OccupancyGrid out(width, height, r, Pose2{x0 * r, y0 * r, 0.0});
  ResampleRigid(source, to_from_source.inverse(), &out);
  return out;
}

}  // namespace fleetmap::sim
