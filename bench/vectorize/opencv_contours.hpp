#pragma once

// The OpenCV baseline of the vectorize benchmark (data/maps/SOURCES.md): findContours(RETR_LIST,
// CHAIN_APPROX_SIMPLE) on the occupied cells, then approxPolyDP at the same epsilon (in cells).
// Split in two so the benchmark times only what OpenCV does, then converts the result into a
// VectorMap in the map frame for the Validator (contour pixel (col, row) -> that cell's centre).

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::bench {

using Contours = std::vector<std::vector<cv::Point>>;

// 255 on occupied cells (default thresholds), 0 elsewhere. Mask row y is grid row y, so contour
// pixels are grid cells.
cv::Mat OccupiedMask(const grid::OccupancyGrid& grid);

// The contours of the mask's occupied regions, each simplified by approxPolyDP.
Contours OpenCvVectorize(const cv::Mat& mask, double epsilon_cells);

// A closed contour of n >= 3 vertices becomes a closed polyline, two vertices an open one (one
// segment), one vertex a point obstacle.
vector_map::VectorMap ContoursToVectorMap(const Contours& contours, const grid::OccupancyGrid& grid,
                                          double epsilon);

}  // namespace fleetmap::bench
