#include "bench/vectorize/vertex_breakdown.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include <opencv2/imgproc.hpp>

namespace fleetmap::bench {
namespace {

size_t ClassOf(int cells) {
  size_t size_class = 0;
  while (size_class < kComponentClassUpperBounds.size() &&
         cells > kComponentClassUpperBounds[size_class]) {
    ++size_class;
  }
  return size_class;
}

// The label of the occupied cell whose centre is nearest to `point`, within `epsilon` metres.
std::optional<int> NearestComponent(const grid::OccupancyGrid& grid, const cv::Mat& labels,
                                    const Point2& point, double epsilon) {
  // The grid is axis-aligned (the benchmark checks it). A vertex may lie just outside the grid
  // (a line end on its border), so the window is clamped rather than the vertex looked up.
  const Point2 cell = (point - grid.CellCenter(0, 0)) / grid.resolution();
  const int cx = static_cast<int>(std::lround(cell.x()));
  const int cy = static_cast<int>(std::lround(cell.y()));
  const int reach = static_cast<int>(std::ceil(epsilon / grid.resolution())) + 1;
  std::optional<int> nearest;
  // A vertex may lie exactly epsilon from its cell; the cells -> metres conversion rounds.
  double best = epsilon * epsilon * (1.0 + 1e-6);
  for (int y = std::max(0, cy - reach); y <= std::min(grid.height() - 1, cy + reach); ++y) {
    for (int x = std::max(0, cx - reach); x <= std::min(grid.width() - 1, cx + reach); ++x) {
      const int label = labels.at<int>(y, x);
      if (label == 0) continue;
      const double distance = (grid.CellCenter(x, y) - point).squaredNorm();
      if (distance <= best) {
        best = distance;
        nearest = label;
      }
    }
  }
  return nearest;
}

}  // namespace

std::string ComponentClassName(size_t size_class) {
  char name[32];
  if (size_class >= kComponentClassUpperBounds.size()) {
    std::snprintf(name, sizeof(name), ">%d", kComponentClassUpperBounds.back());
    return name;
  }
  const int lower = size_class == 0 ? 1 : kComponentClassUpperBounds[size_class - 1] + 1;
  const int upper = kComponentClassUpperBounds[size_class];
  if (lower == upper) {
    std::snprintf(name, sizeof(name), "%d", lower);
  } else {
    std::snprintf(name, sizeof(name), "%d-%d", lower, upper);
  }
  return name;
}

VertexBreakdown& VertexBreakdown::operator+=(const VertexBreakdown& other) {
  for (size_t i = 0; i < kComponentClasses; ++i) {
    components[i] += other.components[i];
    ours_vertices[i] += other.ours_vertices[i];
    opencv_vertices[i] += other.opencv_vertices[i];
  }
  ours_unattributed += other.ours_unattributed;
  return *this;
}

VertexBreakdown BreakDownVertices(const grid::OccupancyGrid& grid, const cv::Mat& occupied,
                                  const vector_map::VectorMap& ours, const Contours& opencv,
                                  double epsilon) {
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int count = cv::connectedComponentsWithStats(occupied, labels, stats, centroids, 8, CV_32S);
  auto class_of_label = [&stats](int label) {
    return ClassOf(stats.at<int>(label, cv::CC_STAT_AREA));
  };
  VertexBreakdown breakdown;
  for (int label = 1; label < count; ++label) ++breakdown.components[class_of_label(label)];
  for (const std::vector<cv::Point>& contour : opencv) {
    for (const cv::Point& pixel : contour) {
      ++breakdown.opencv_vertices[class_of_label(labels.at<int>(pixel.y, pixel.x))];
    }
  }
  for (const vector_map::Polyline& polyline : ours.obstacles) {
    for (const Point2& vertex : polyline.points) {
      const std::optional<int> label = NearestComponent(grid, labels, vertex, epsilon);
      if (label) {
        ++breakdown.ours_vertices[class_of_label(*label)];
      } else {
        ++breakdown.ours_unattributed;
      }
    }
  }
  return breakdown;
}

}  // namespace fleetmap::bench
