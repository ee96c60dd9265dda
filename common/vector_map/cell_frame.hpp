#pragma once

// Conversion between the map frame (metres) and "cell coordinates" of a grid geometry, in which
// the centre of cell (x, y) is the point (x, y). Algorithms work in cell coordinates (cell centres
// are integers, so distances between them are exact); results are converted once at the end.

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::vector_map {

class CellFrame {
 public:
  CellFrame(double resolution, const Pose2& origin);
  explicit CellFrame(const grid::OccupancyGrid& grid)
      : CellFrame(grid.resolution(), grid.origin()) {}

  // For integer cells this computes exactly what OccupancyGrid::CellCenter computes.
  Point2 ToMap(const Point2& cell_point) const {
    return map_from_grid_ *
           Point2((cell_point.x() + 0.5) * resolution_, (cell_point.y() + 0.5) * resolution_);
  }
  Point2 ToCell(const Point2& map_point) const {
    const Point2 in_grid = grid_from_map_ * map_point;
    return Point2(in_grid.x() / resolution_ - 0.5, in_grid.y() / resolution_ - 0.5);
  }
  double resolution() const { return resolution_; }

 private:
  double resolution_;
  Transform2 map_from_grid_;
  Transform2 grid_from_map_;
};

}  // namespace fleetmap::vector_map
