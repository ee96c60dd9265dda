#pragma once

// A window of a grid as one flat byte image of cell flags, built by one tight scan of the grid
// rows: occupancy, the delimitation P (ALGORITHMS.md 1) and working bits the vectorizer sets while
// it runs (skeleton, anchor, covered, visited). Every stage of kDefault reads and writes cells
// through Index() and the neighbour offsets, so no stage pays a bounds check or a virtual call per
// cell, and the work after the scan is proportional to the occupied cells, not to the grid.
//
// The image covers the rectangle plus `margin` cells on every side (not clamped to the grid: cells
// outside the grid are simply not occupied, as ALGORITHMS.md reads them), plus one more ring so
// that P is exact everywhere inside the margin (`margin` >= 1). P of a window is the whole grid's
// P restricted to it, so neighbouring tiles agree on it.
//
// Thread-safety: not thread-safe; one CellRaster per call.

#include <cstdint>
#include <vector>

#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::vector_map {

using grid::CellRect;

class CellRaster {
 public:
  static constexpr uint8_t kOccupied = 1;
  static constexpr uint8_t kDelimitation = 2;
  static constexpr uint8_t kOwned = 4;     // a P point inside the rectangle (must be covered)
  static constexpr uint8_t kSkeleton = 8;  // set by thinning
  static constexpr uint8_t kAnchor = 16;   // occupied cell just outside the rectangle
  static constexpr uint8_t kCovered = 32;  // P point within epsilon of an emitted segment
  static constexpr uint8_t kVisited = 64;  // scratch bit for walks

  CellRaster(const grid::OccupancyGrid& grid, const CellRect& rect, int margin,
             const grid::StateThresholds& thresholds);
  ~CellRaster();
  CellRaster(const CellRaster&) = delete;
  CellRaster& operator=(const CellRaster&) = delete;

  int Index(int x, int y) const { return (y - y0_) * stride_ + (x - x0_); }
  int X(int index) const { return index % stride_ + x0_; }
  int Y(int index) const { return index / stride_ + y0_; }
  bool Contains(int x, int y) const {
    return x >= x0_ && y >= y0_ && x < x0_ + stride_ && y < y0_ + rows_;
  }
  int stride() const { return stride_; }
  // The cells the image covers (Index(x, y) = (y - y0) * width + (x - x0)); a copy in a local lets
  // a loop that stores bytes keep the bounds in registers.
  CellRect window() const { return CellRect{x0_, y0_, stride_, rows_}; }
  size_t size() const { return flags_.size(); }
  const CellRect& rect() const { return rect_; }

  uint8_t& at(int index) { return flags_[index]; }
  uint8_t at(int index) const { return flags_[index]; }
  bool Has(int index, uint8_t bits) const { return (flags_[index] & bits) != 0; }
  // The flags by raster index, for cell loops that keep the pointer in a local.
  const uint8_t* data() const { return flags_.data(); }
  // Bounds-checked (false outside the image), for geometric queries that may stray.
  bool IsDelimitation(int x, int y) const {
    return Contains(x, y) && (flags_[Index(x, y)] & kDelimitation) != 0;
  }

  // P points inside the rectangle, in row-major order (raster indices).
  const std::vector<int>& owned_delimitation() const { return owned_; }
  // Occupied cells of the rectangle grown by one cell, in row-major order (raster indices).
  const std::vector<int>& occupied_near_rect() const { return occupied_; }

  // Clears `bits` on every cell of the list.
  void Clear(const std::vector<int>& indices, uint8_t bits) {
    for (const int i : indices) flags_[i] &= static_cast<uint8_t>(~bits);
  }

 private:
  CellRect rect_;
  int x0_ = 0;
  int y0_ = 0;
  int stride_ = 0;
  int rows_ = 0;
  std::vector<uint8_t> flags_;
  std::vector<int> owned_;
  std::vector<int> occupied_;
};

}  // namespace fleetmap::vector_map
