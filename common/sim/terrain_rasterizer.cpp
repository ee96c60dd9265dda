#include "common/sim/terrain_rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/core/number_format.hpp"

namespace fleetmap::sim {
namespace {

double SegmentDistance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

void FillCapsule(const Point2& a, const Point2& b, double radius, grid::OccupancyGrid* grid) {
  const double res = grid->resolution();
  const int x0 = std::max(0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - radius) / res)));
  const int y0 = std::max(0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - radius) / res)));
  const int x1 = std::min(grid->width() - 1,
                          static_cast<int>(std::floor((std::max(a.x(), b.x()) + radius) / res)));
  const int y1 = std::min(grid->height() - 1,
                          static_cast<int>(std::floor((std::max(a.y(), b.y()) + radius) / res)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Point2 centre((x + 0.5) * res, (y + 0.5) * res);
      if (SegmentDistance(centre, a, b) <= radius) grid->at(x, y) = grid::kOccupiedValue;
    }
  }
}

// Cells whose centre is inside the polygon (even-odd rule on each row's centre line).
void FillPolygon(const std::vector<Point2>& points, grid::OccupancyGrid* grid) {
  if (points.size() < 3) return;
  const double res = grid->resolution();
  double min_y = points[0].y(), max_y = points[0].y();
  for (const Point2& p : points) {
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
  }
  const int y0 = std::max(0, static_cast<int>(std::floor(min_y / res)));
  const int y1 = std::min(grid->height() - 1, static_cast<int>(std::floor(max_y / res)));
  std::vector<double> crossings;
  for (int y = y0; y <= y1; ++y) {
    const double cy = (y + 0.5) * res;
    crossings.clear();
    for (size_t i = 0; i < points.size(); ++i) {
      const Point2& p = points[i];
      const Point2& q = points[(i + 1) % points.size()];
      if ((p.y() <= cy) == (q.y() <= cy)) continue;
      crossings.push_back(p.x() + (cy - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t i = 0; i + 1 < crossings.size(); i += 2) {
      // Cell centres (x + 0.5) * res inside [crossings[i], crossings[i + 1]].
      const int xa = std::max(0, static_cast<int>(std::ceil(crossings[i] / res - 0.5)));
      const int xb =
          std::min(grid->width() - 1, static_cast<int>(std::floor(crossings[i + 1] / res - 0.5)));
      for (int x = xa; x <= xb; ++x) grid->at(x, y) = grid::kOccupiedValue;
    }
  }
}

}  // namespace

StatusOr<grid::OccupancyGrid> RasterizeTerrain(const Terrain& terrain, double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    return InvalidArgumentError("resolution " + ShortNumber(resolution) +
                                " m is invalid: it must be > 0");
  }
  const double side = std::ceil(terrain.size / resolution - 1e-9);
  if (!(side * side <= static_cast<double>(kMaxGroundTruthCells))) {
    return InvalidArgumentError("resolution " + ShortNumber(resolution) + " m on a " +
                                ShortNumber(terrain.size) + " m terrain needs more than " +
                                std::to_string(kMaxGroundTruthCells) + " cells");
  }
  const int cells = std::max(1, static_cast<int>(side));
  grid::OccupancyGrid grid(cells, cells, resolution, Pose2{}, grid::kFreeValue);
  // Any point of a centre line lies in a cell whose centre is within res * sqrt(2) / 2 of it.
  const double min_radius = resolution * std::sqrt(0.5);
  for (const Wall& wall : terrain.walls) {
    FillCapsule(wall.a, wall.b, std::max(wall.thickness / 2.0, min_radius), &grid);
  }
  for (const Door& door : terrain.doors) {
    if (!door.open) FillCapsule(door.a, door.b, std::max(door.thickness / 2.0, min_radius), &grid);
  }
  for (const SolidPolygon& polygon : terrain.polygons) FillPolygon(polygon.points, &grid);
  return grid;
}

}  // namespace fleetmap::sim
