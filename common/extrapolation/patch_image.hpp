#pragma once

// A binary image of points on a plane patch: cells of a fixed size in the plane's (a, b)
// coordinates, with 8-connected components. The detectors use it to keep one contiguous patch of
// a RANSAC plane's inliers (a plane through two separate walls is not one surface) and to measure
// its area, extents and corners.
//
// Thread-safety: not thread-safe; one owner.

#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::extrapolation {

class PatchImage {
 public:
  // `coordinates[i]` is point i in the plane (metres); `cell` the cell side (> 0).
  PatchImage(const std::vector<Point2>& coordinates, double cell);

  // Indices (into `coordinates`) of the points in each 8-connected component, largest first.
  std::vector<std::vector<int>> Components() const;

  // Cells occupied by the points `indices` (each cell counted once).
  int CellCount(const std::vector<int>& indices) const;
  // Whether some cell within `radius_cells` of the cell holding `p` holds one of the points.
  bool Occupied(const Point2& p, int radius_cells) const;

  double cell() const { return cell_; }

 private:
  int Index(int x, int y) const { return y * width_ + x; }
  int CellX(double a) const;
  int CellY(double b) const;

  double cell_;
  double min_a_ = 0;
  double min_b_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::vector<int> cell_of_point_;
  std::vector<std::vector<int>> points_in_cell_;
};

}  // namespace fleetmap::extrapolation
