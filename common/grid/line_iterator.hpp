#pragma once

// The one walk along a straight line of grid cells (8-connected Bresenham): every module that
// needs the cells between two cells iterates a GridLine instead of stepping an error term itself.
//
//   for (const grid::CellIndex cell : grid::GridLine(from, to)) { ... }
//
// Contract:
//  - Both ends are included: the first cell is `from`, the last is `to`; from == to gives that one
//    cell. A caller that wants to leave an end out (or treat it differently) says so where it
//    walks, e.g. by comparing the cell with `to`.
//  - The cells come in order from `from` to `to`, each a king's move (one step in x, y or both)
//    from the one before, never repeating: max(|dx|, |dy|) + 1 cells in all.
//  - Where the exact line passes midway between two cells, the walk takes the diagonal step first
//    (the cell nearer `to`). So mirroring a line in x or y, or swapping x and y, mirrors or swaps
//    its cells; but a line walked backwards may differ from the forward one in those tie cells.
//  - Cells are not clipped to any grid: a line that leaves the grid yields cells outside it, and
//    the caller checks each one it looks up.
//
// Thread-safety: a GridLine and its iterators are values; copy them freely.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iterator>

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::grid {

// A forward iterator over the cells of one GridLine.
class LineIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = CellIndex;
  using difference_type = std::ptrdiff_t;
  using pointer = const CellIndex*;
  using reference = const CellIndex&;

  // The past-the-end iterator of every line.
  LineIterator() = default;
  // The first cell of the line from `from` to `to`.
  LineIterator(const CellIndex& from, const CellIndex& to)
      : cell_(from),
        to_(to),
        dx_(std::abs(static_cast<int64_t>(to.x) - from.x)),
        dy_(-std::abs(static_cast<int64_t>(to.y) - from.y)),
        step_x_(from.x < to.x ? 1 : -1),
        step_y_(from.y < to.y ? 1 : -1),
        error_(dx_ + dy_),
        done_(false) {}

  reference operator*() const { return cell_; }
  pointer operator->() const { return &cell_; }

  LineIterator& operator++() {
    if (cell_ == to_) {
      done_ = true;
      return *this;
    }
    // error_ is the error of the diagonal step; doubled, it tells which axes to step.
    const int64_t doubled = 2 * error_;
    if (doubled >= dy_) {
      error_ += dy_;
      cell_.x += step_x_;
    }
    if (doubled <= dx_) {
      error_ += dx_;
      cell_.y += step_y_;
    }
    return *this;
  }
  LineIterator operator++(int) {
    LineIterator before = *this;
    ++*this;
    return before;
  }

  // Iterators of the same line compare equal at the same cell; every finished one equals end().
  friend bool operator==(const LineIterator& a, const LineIterator& b) {
    return a.done_ == b.done_ && (a.done_ || a.cell_ == b.cell_);
  }

 private:
  CellIndex cell_;
  CellIndex to_;
  int64_t dx_ = 0;  // |to.x - from.x|
  int64_t dy_ = 0;  // -|to.y - from.y|
  int step_x_ = 1;
  int step_y_ = 1;
  int64_t error_ = 0;
  bool done_ = true;
};

// The cells of the line from `from` to `to`, both included (see the contract above).
class GridLine {
 public:
  GridLine(const CellIndex& from, const CellIndex& to) : from_(from), to_(to) {}

  LineIterator begin() const { return LineIterator(from_, to_); }
  LineIterator end() const { return LineIterator(); }
  // How many cells the walk yields: max(|dx|, |dy|) + 1.
  int64_t size() const {
    const int64_t dx = std::abs(static_cast<int64_t>(to_.x) - from_.x);
    const int64_t dy = std::abs(static_cast<int64_t>(to_.y) - from_.y);
    return (dx > dy ? dx : dy) + 1;
  }

 private:
  CellIndex from_;
  CellIndex to_;
};

}  // namespace fleetmap::grid
