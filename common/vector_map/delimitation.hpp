#pragma once

// The obstacle delimitation P of a grid (ALGORITHMS.md 1): centres of occupied cells with at least
// one 4-neighbour that is not occupied. Cells outside the grid count as not occupied, so an
// obstacle touching the grid border is delimited there too (the grid says nothing beyond it).

#include <cstdint>
#include <vector>

#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::vector_map {

using grid::CellRect;

// The whole grid as a rectangle.
CellRect FullRect(const grid::OccupancyGrid& grid);

// Occupancy and delimitation flags of a window of a grid (a rectangle plus a margin, clamped to the
// grid). Outside the window, queries fall back to reading the grid. Not thread-safe to build;
// const queries may run concurrently.
class Delimitation {
 public:
  Delimitation(const grid::OccupancyGrid& grid, const CellRect& rect, int margin,
               const grid::StateThresholds& thresholds);

  // False outside the grid.
  bool Occupied(int x, int y) const {
    if (window_.Contains(x, y)) return (flags_[Index(x, y)] & kOccupiedFlag) != 0;
    return OccupiedInGrid(x, y);
  }
  // True for cells of P (occupied with a 4-neighbour not occupied).
  bool IsDelimitation(int x, int y) const {
    if (window_.Contains(x, y)) return (flags_[Index(x, y)] & kDelimitationFlag) != 0;
    return DelimitationInGrid(x, y);
  }
  const CellRect& window() const { return window_; }
  const grid::OccupancyGrid& grid() const { return *grid_; }

 private:
  static constexpr uint8_t kOccupiedFlag = 1;
  static constexpr uint8_t kDelimitationFlag = 2;

  size_t Index(int x, int y) const {
    return static_cast<size_t>(y - window_.y0) * window_.width + (x - window_.x0);
  }
  bool OccupiedInGrid(int x, int y) const;
  bool DelimitationInGrid(int x, int y) const;

  const grid::OccupancyGrid* grid_;
  grid::StateThresholds thresholds_;
  CellRect window_;
  std::vector<uint8_t> flags_;
};

}  // namespace fleetmap::vector_map
