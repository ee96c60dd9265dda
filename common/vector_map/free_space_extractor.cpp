#include "common/vector_map/free_space_extractor.hpp"

#include <opencv2/imgproc.hpp>

namespace fleetmap::vector_map {

std::vector<CellPolygon> ExtractFreeSpace(const grid::OccupancyGrid& grid, const CellRect& rect,
                                          const grid::StateThresholds& thresholds,
                                          double epsilon_cells) {
  std::vector<CellPolygon> polygons;
  if (rect.empty()) return polygons;
  cv::Mat mask(rect.height, rect.width, CV_8UC1);
  bool any = false;
  for (int y = 0; y < rect.height; ++y) {
    uint8_t* row = mask.ptr<uint8_t>(y);
    for (int x = 0; x < rect.width; ++x) {
      const bool free =
          grid::StateOf(grid.at(rect.x0 + x, rect.y0 + y), thresholds) == grid::CellState::kFree;
      row[x] = free ? 255 : 0;
      any = any || free;
    }
  }
  if (!any) return polygons;
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  auto convert = [&](const std::vector<cv::Point>& contour) {
    std::vector<cv::Point> simplified;
    cv::approxPolyDP(contour, simplified, epsilon_cells, /*closed=*/true);
    std::vector<Point2> ring;
    ring.reserve(simplified.size());
    for (const cv::Point& p : simplified) ring.emplace_back(rect.x0 + p.x, rect.y0 + p.y);
    return ring;
  };
  for (size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0) continue;  // a hole; handled with its parent
    CellPolygon polygon;
    polygon.outer = convert(contours[i]);
    for (int child = hierarchy[i][2]; child >= 0; child = hierarchy[child][0]) {
      polygon.holes.push_back(convert(contours[child]));
    }
    polygons.push_back(std::move(polygon));
  }
  return polygons;
}

}  // namespace fleetmap::vector_map
