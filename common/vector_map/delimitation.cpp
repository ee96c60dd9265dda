#include "common/vector_map/delimitation.hpp"

#include <algorithm>

namespace fleetmap::vector_map {

CellRect FullRect(const grid::OccupancyGrid& grid) {
  return CellRect{0, 0, grid.width(), grid.height()};
}

Delimitation::Delimitation(const grid::OccupancyGrid& grid, const CellRect& rect, int margin,
                           const grid::StateThresholds& thresholds)
    : grid_(&grid), thresholds_(thresholds) {
  const int x0 = std::max(0, rect.x0 - margin);
  const int y0 = std::max(0, rect.y0 - margin);
  const int x1 = std::min(grid.width(), rect.x0 + rect.width + margin);
  const int y1 = std::min(grid.height(), rect.y0 + rect.height + margin);
  window_ = CellRect{x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
  flags_.assign(static_cast<size_t>(window_.cell_count()), 0);
  for (int y = y0; y < y1; ++y) {
    const int8_t* row = grid.data().data() + static_cast<size_t>(y) * grid.width();
    uint8_t* out = flags_.data() + Index(x0, y);
    for (int x = x0; x < x1; ++x) {
      const int8_t v = row[x];
      // Same rule as grid::StateOf, inlined: values outside 0..100 are unknown.
      out[x - x0] = (v >= 0 && v <= 100 && v / 100.0 > thresholds.occupied) ? kOccupiedFlag : 0;
    }
  }
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      uint8_t& f = flags_[Index(x, y)];
      if (!(f & kOccupiedFlag)) continue;
      const bool boundary =
          !Occupied(x - 1, y) || !Occupied(x + 1, y) || !Occupied(x, y - 1) || !Occupied(x, y + 1);
      if (boundary) f |= kDelimitationFlag;
    }
  }
}

bool Delimitation::OccupiedInGrid(int x, int y) const {
  if (!grid_->Contains(x, y)) return false;
  return grid::StateOf(grid_->at(x, y), thresholds_) == grid::CellState::kOccupied;
}

bool Delimitation::DelimitationInGrid(int x, int y) const {
  if (!OccupiedInGrid(x, y)) return false;
  return !OccupiedInGrid(x - 1, y) || !OccupiedInGrid(x + 1, y) || !OccupiedInGrid(x, y - 1) ||
         !OccupiedInGrid(x, y + 1);
}

}  // namespace fleetmap::vector_map
