#include "cli/opencv_contours.hpp"

#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace fleetmap::cli {

cv::Mat OccupiedMask(const grid::OccupancyGrid& grid) {
  cv::Mat mask(grid.height(), grid.width(), CV_8UC1);
  for (int y = 0; y < grid.height(); ++y) {
    uint8_t* row = mask.ptr<uint8_t>(y);
    for (int x = 0; x < grid.width(); ++x) {
      row[x] = grid.StateAt(x, y) == grid::CellState::kOccupied ? 255 : 0;
    }
  }
  return mask;
}

Contours OpenCvVectorize(const cv::Mat& mask, double epsilon_cells) {
  Contours contours;
  cv::findContours(mask, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
  Contours simplified(contours.size());
  for (size_t i = 0; i < contours.size(); ++i) {
    cv::approxPolyDP(contours[i], simplified[i], epsilon_cells, /*closed=*/true);
  }
  return simplified;
}

vector_map::VectorMap ContoursToVectorMap(const Contours& contours,
                                          const grid::OccupancyGrid& grid, double epsilon) {
  vector_map::VectorMap map;
  map.resolution = grid.resolution();
  map.epsilon = epsilon;
  for (const std::vector<cv::Point>& contour : contours) {
    if (contour.empty()) continue;
    vector_map::Polyline polyline;
    for (const cv::Point& pixel : contour) polyline.points.push_back(grid.CellCenter(pixel.x, pixel.y));
    polyline.closed = polyline.points.size() >= 3;
    map.obstacles.push_back(std::move(polyline));
  }
  return map;
}

}  // namespace fleetmap::cli
