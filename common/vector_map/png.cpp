#include "common/vector_map/png.hpp"

#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/vector_map/cell_frame.hpp"

namespace fleetmap::vector_map {

StatusOr<std::vector<uint8_t>> EncodeGridPng(const grid::OccupancyGrid& grid) {
  if (grid.empty()) return InvalidArgumentError("png: cannot encode an empty grid");
  cv::Mat image(grid.height(), grid.width(), CV_8UC1);
  for (int y = 0; y < grid.height(); ++y) {
    uint8_t* row = image.ptr<uint8_t>(grid.height() - 1 - y);
    for (int x = 0; x < grid.width(); ++x) {
      switch (grid.StateAt(x, y)) {
        case grid::CellState::kOccupied:
          row[x] = 0;
          break;
        case grid::CellState::kFree:
          row[x] = 254;
          break;
        case grid::CellState::kUnknown:
          row[x] = 205;
          break;
      }
    }
  }
  std::vector<uint8_t> bytes;
  if (!cv::imencode(".png", image, bytes)) return InternalError("png: OpenCV could not encode");
  return bytes;
}

StatusOr<std::vector<uint8_t>> RenderVectorMapPng(const VectorMap& map,
                                                  const grid::OccupancyGrid& like,
                                                  const VectorPngOptions& options) {
  if (like.empty()) return InvalidArgumentError("png: empty target geometry");
  if (options.pixels_per_cell < 1) return InvalidArgumentError("png: pixels_per_cell must be >= 1");
  const int s = options.pixels_per_cell;
  const int width = like.width() * s;
  const int height = like.height() * s;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(180, 180, 180));
  const CellFrame frame(like);
  constexpr int kShift = 4;
  auto to_pixel = [&](const Point2& p) {
    const Point2 c = frame.ToCell(p);
    const double px = (c.x() + 0.5) * s;
    const double py = height - (c.y() + 0.5) * s;
    return cv::Point(static_cast<int>(std::lround(px * (1 << kShift))),
                     static_cast<int>(std::lround(py * (1 << kShift))));
  };
  for (const FreePolygon& polygon : map.free_space) {
    std::vector<std::vector<cv::Point>> rings;
    auto add = [&](const std::vector<Point2>& ring) {
      auto& out = rings.emplace_back();
      for (const Point2& p : ring) out.push_back(to_pixel(p));
    };
    if (polygon.outer.empty()) continue;
    add(polygon.outer);
    for (const auto& hole : polygon.holes) add(hole);
    cv::fillPoly(image, rings, cv::Scalar(250, 250, 250), cv::LINE_8, kShift);
  }
  for (const Polyline& polyline : map.obstacles) {
    std::vector<cv::Point> points;
    for (const Point2& p : polyline.points) points.push_back(to_pixel(p));
    if (points.size() == 1) points.push_back(points.front());
    cv::polylines(image, points, polyline.closed, cv::Scalar(40, 40, 40), 1, cv::LINE_AA, kShift);
    if (options.draw_vertices) {
      for (const cv::Point& p : points) {
        cv::circle(image, p, (1 << kShift) * std::max(1, s / 2), cv::Scalar(40, 40, 220), -1,
                   cv::LINE_8, kShift);
      }
    }
  }
  std::vector<uint8_t> bytes;
  if (!cv::imencode(".png", image, bytes)) return InternalError("png: OpenCV could not encode");
  return bytes;
}

}  // namespace fleetmap::vector_map
