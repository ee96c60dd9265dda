#pragma once

// How far each free cell of a grid is from everything a robot may not touch: occupied and unknown
// cells, and the outside of the grid. The distance transform of free space (OpenCV's exact
// Euclidean one), turned into a lower bound on the distance from a cell's centre to the nearest
// point of a blocked cell (the centre distance minus half a cell's diagonal) and capped. A segment
// keeps a clearance when a dense walk along it proves it from these bounds (SegmentClearance):
// the check every edge of the route graph passes and that the tests repeat independently.
//
// Thread-safety: a value; const methods may be called from any number of threads.

#include <cstdint>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::route_graph {

class ClearanceMap {
 public:
  ClearanceMap() = default;
  // The whole grid: free cells are those grid::StateOf reads as kFree with `thresholds`.
  ClearanceMap(const grid::OccupancyGrid& grid, double cap,
               const grid::StateThresholds& thresholds = {});

  // Recomputes the cells of `rect` from `grid` (same geometry as the one this map was made of),
  // after cells inside `rect` changed; every other cell keeps its value. Exact: the cells read
  // around `rect` reach as far as the cap.
  void Update(const grid::OccupancyGrid& grid, const grid::CellRect& rect);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  double cap() const { return cap_; }
  const Point2& origin() const { return origin_; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  // Metres; <= 0 for a blocked cell. Capped at cap().
  float at(int x, int y) const { return clearance_[static_cast<size_t>(y) * width_ + x]; }
  const std::vector<float>& values() const { return clearance_; }

  Point2 CellCenter(int x, int y) const {
    return origin_ + Point2((x + 0.5) * resolution_, (y + 0.5) * resolution_);
  }
  // The cell holding a map-frame point (may be outside the grid).
  grid::CellIndex CellOf(const Point2& point) const;

  // A proven lower bound on the clearance of every point of the segment from `a` to `b` (map
  // frame), capped; a segment leaving the grid has none (a negative value). Walks the segment in
  // steps of a quarter cell and bounds each point by the cells around it.
  double SegmentClearance(const Point2& a, const Point2& b) const;
  // Whether every point of the segment keeps `required` metres (SegmentClearance >= required),
  // stopping at the first point that does not.
  bool SegmentKeeps(const Point2& a, const Point2& b, double required) const;

 private:
  // A lower bound on the clearance at `point`; stops looking once it reaches `enough`.
  double PointBound(const Point2& point, double enough) const;
  template <typename Visit>
  bool WalkSegment(const Point2& a, const Point2& b, double enough, Visit&& visit) const;

  int width_ = 0;
  int height_ = 0;
  double resolution_ = 0.05;
  double cap_ = 0.0;
  Point2 origin_ = Point2::Zero();
  grid::StateThresholds thresholds_;
  std::vector<float> clearance_;
};

}  // namespace fleetmap::route_graph
