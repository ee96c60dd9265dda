#include "bench/vectorize/opencv_contours.hpp"

#include <array>
#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace fleetmap::bench {

cv::Mat OccupiedMask(const grid::OccupancyGrid& grid) {
  // One table lookup per cell, as a tuned baseline would do (not a threshold test per cell).
  std::array<uint8_t, 256> table;
  for (int value = -128; value < 128; ++value) {
    table[static_cast<uint8_t>(value)] =
        grid::StateOf(static_cast<int8_t>(value)) == grid::CellState::kOccupied ? 255 : 0;
  }
  cv::Mat mask(grid.height(), grid.width(), CV_8UC1);
  const int8_t* cells = grid.data().data();
  for (int y = 0; y < grid.height(); ++y) {
    uint8_t* row = mask.ptr<uint8_t>(y);
    const int8_t* source = cells + static_cast<size_t>(y) * grid.width();
    for (int x = 0; x < grid.width(); ++x) row[x] = table[static_cast<uint8_t>(source[x])];
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

vector_map::VectorMap ContoursToVectorMap(const Contours& contours, const grid::OccupancyGrid& grid,
                                          double epsilon) {
  vector_map::VectorMap map;
  map.resolution = grid.resolution();
  map.epsilon = epsilon;
  for (const std::vector<cv::Point>& contour : contours) {
    if (contour.empty()) continue;
    vector_map::Polyline polyline;
    for (const cv::Point& pixel : contour)
      polyline.points.push_back(grid.CellCenter(pixel.x, pixel.y));
    polyline.closed = polyline.points.size() >= 3;
    map.obstacles.push_back(std::move(polyline));
  }
  return map;
}

}  // namespace fleetmap::bench
