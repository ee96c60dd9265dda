#pragma once

// Explored free space of a rectangle of cells as polygons with holes, in cell coordinates
// (CellFrame). Outlines pass through the centres of the region's boundary cells (OpenCV border
// following) and are simplified with Douglas-Peucker at `epsilon_cells`; the Rasterizer fills a
// polygon including its outline, which rebuilds an unsimplified region exactly.

#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/delimitation.hpp"

namespace fleetmap::vector_map {

struct CellPolygon {
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> holes;
};

std::vector<CellPolygon> ExtractFreeSpace(const grid::OccupancyGrid& grid, const CellRect& rect,
                                          const grid::StateThresholds& thresholds,
                                          double epsilon_cells);

}  // namespace fleetmap::vector_map
