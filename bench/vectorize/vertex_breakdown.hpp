#pragma once

// Where a vectorizer spends its vertices, for `fleetmap bench vectorize`: the occupied cells'
// 8-connected components, by size, and the vertices each method puts on them. A speck or a blob
// of two or three cells costs any valid method about one vertex, whatever it does with walls, so
// the share of vertices on small components bounds how far a centre-line method can go below a
// contour tracer; the large components are where one centre line instead of two outlines pays.

#include <array>
#include <cstdint>
#include <string>

#include <opencv2/core/mat.hpp>

#include "bench/vectorize/opencv_contours.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::bench {

// Component size classes, by cell count: 1, 2-3, 4-10, 11-50, more than 50.
inline constexpr std::array<int, 4> kComponentClassUpperBounds = {1, 3, 10, 50};
inline constexpr size_t kComponentClasses = kComponentClassUpperBounds.size() + 1;

// "1", "2-3", "4-10", "11-50", ">50".
std::string ComponentClassName(size_t size_class);

struct VertexBreakdown {
  std::array<int64_t, kComponentClasses> components{};
  std::array<int64_t, kComponentClasses> ours_vertices{};
  std::array<int64_t, kComponentClasses> opencv_vertices{};
  // Vertices of ours with no occupied cell within `epsilon` (none when the continuity constraint
  // holds); counted here so that the classes add up to the total.
  int64_t ours_unattributed = 0;

  VertexBreakdown& operator+=(const VertexBreakdown& other);
};

// `occupied` is OccupiedMask(grid). A vertex of ours counts for the component of the occupied cell
// whose centre is nearest to it (within `epsilon` metres); an OpenCV vertex is a cell of its
// component.
VertexBreakdown BreakDownVertices(const grid::OccupancyGrid& grid, const cv::Mat& occupied,
                                  const vector_map::VectorMap& ours, const Contours& opencv,
                                  double epsilon);

}  // namespace fleetmap::bench
