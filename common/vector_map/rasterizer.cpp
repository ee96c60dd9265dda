#include "common/vector_map/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

StatusOr<grid::OccupancyGrid> Rasterizer::Rasterize(const VectorMap& map, int width, int height,
                                                    double resolution, const Pose2& origin) const {
  if (width < 0 || height < 0) return InvalidArgumentError("rasterize: negative grid size");
  if (!(resolution > 0.0)) return InvalidArgumentError("rasterize: resolution must be > 0");
  const double fixed_radius =
      options_.occupied_radius > 0.0 ? options_.occupied_radius : map.epsilon / 2.0;
  if (!options_.use_half_width && !(fixed_radius > 0.0)) {
    return InvalidArgumentError("rasterize: no occupied radius (map epsilon is not positive)");
  }
  const double min_half_width =
      options_.min_half_width > 0.0 ? options_.min_half_width : resolution / 2.0;
  grid::OccupancyGrid out(width, height, resolution, origin, grid::kUnknownValue);
  if (out.empty()) return out;
  const CellFrame frame(resolution, origin);

  // Free polygons, filled with sub-cell precision (8 fractional bits); cell (x, y) is pixel (x, y).
  cv::Mat free_mask = cv::Mat::zeros(height, width, CV_8UC1);
  constexpr int kShift = 8;
  constexpr double kScale = 1 << kShift;
  auto to_pixels = [&](const std::vector<Point2>& ring) {
    std::vector<cv::Point> pixels;
    pixels.reserve(ring.size());
    for (const Point2& p : ring) {
      const Point2 c = frame.ToCell(p);
      pixels.emplace_back(static_cast<int>(std::lround(c.x() * kScale)),
                          static_cast<int>(std::lround(c.y() * kScale)));
    }
    return pixels;
  };
  std::vector<std::vector<cv::Point>> rings;
  for (const FreePolygon& polygon : map.free_space) {
    rings.clear();
    if (polygon.outer.empty()) continue;
    // Wholly off the grid: nothing to fill, and pixel coordinates could overflow.
    double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
    for (const Point2& p : polygon.outer) {
      const Point2 c = frame.ToCell(p);
      min_x = std::min(min_x, c.x());
      min_y = std::min(min_y, c.y());
      max_x = std::max(max_x, c.x());
      max_y = std::max(max_y, c.y());
    }
    if (!(max_x >= -1.0 && min_x <= width + 1.0 && max_y >= -1.0 && min_y <= height + 1.0)) {
      continue;
    }
    rings.push_back(to_pixels(polygon.outer));
    for (const auto& hole : polygon.holes) {
      if (!hole.empty()) rings.push_back(to_pixels(hole));
    }
    // The outer outline first (fillPoly drops its edge pixels where a hole outline overlaps).
    cv::fillPoly(free_mask, rings, cv::Scalar(255), cv::LINE_8, kShift);
    cv::polylines(free_mask, std::vector<std::vector<cv::Point>>{rings.front()}, true,
                  cv::Scalar(255), 1, cv::LINE_8, kShift);
  }
  auto& data = out.mutable_data();
  for (int y = 0; y < height; ++y) {
    const uint8_t* row = free_mask.ptr<uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      if (row[x]) data[static_cast<size_t>(y) * width + x] = grid::kFreeValue;
    }
  }

  double r = 0.0;
  double r2 = 0.0;
  // Only the grid's cells are walked, and a segment wholly off the grid is not walked at all:
  // cell coordinates beyond the int range (a tile rasterized under another tile's key) would
  // otherwise make the walk span the whole int range.
  const grid::CellRect cells{0, 0, width, height};
  auto mark = [&](const Point2& a, const Point2& b) {
    if (std::max(a.x(), b.x()) + r < -1.0 || std::min(a.x(), b.x()) - r > width + 1.0 ||
        std::max(a.y(), b.y()) + r < -1.0 || std::min(a.y(), b.y()) - r > height + 1.0 ||
        !std::isfinite(a.x() + a.y() + b.x() + b.y())) {
      return;
    }
    ForEachCellNearSegmentIn(cells, a, b, r, [&](int x, int y) {
      if (PointSegmentDistanceSquared(Point2(x, y), a, b) <= r2) {
        data[static_cast<size_t>(y) * width + x] = grid::kOccupiedValue;
      }
    });
  };
  for (const Polyline& polyline : map.obstacles) {
    std::vector<Point2> pts;
    pts.reserve(polyline.points.size());
    for (const Point2& p : polyline.points) pts.push_back(frame.ToCell(p));
    const double radius =
        options_.use_half_width ? std::max(polyline.half_width, min_half_width) : fixed_radius;
    r = radius / resolution;
    r2 = ToleratedSquare(r);
    if (pts.size() == 1) mark(pts[0], pts[0]);
    for (size_t k = 0; k + 1 < pts.size(); ++k) mark(pts[k], pts[k + 1]);
    if (polyline.closed && pts.size() >= 3) mark(pts.back(), pts.front());
  }
  return out;
}

}  // namespace fleetmap::vector_map
