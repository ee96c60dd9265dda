#pragma once

#include <cstdint>

namespace fleetmap::grid {

// A rectangle of cells [x0, x0 + width) x [y0, y0 + height) of a grid, e.g. one tile's cells.
struct CellRect {
  int x0 = 0;
  int y0 = 0;
  int width = 0;
  int height = 0;

  bool Contains(int x, int y) const {
    return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height;
  }
  bool empty() const { return width <= 0 || height <= 0; }
  int64_t cell_count() const { return static_cast<int64_t>(width) * height; }
  friend bool operator==(const CellRect&, const CellRect&) = default;
};

}  // namespace fleetmap::grid
