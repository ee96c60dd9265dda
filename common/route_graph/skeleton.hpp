#pragma once

// The skeleton of the space a robot fits in: the cells whose clearance reaches the robot's radius
// plus its margin, thinned to one-cell-wide curves that keep the space's topology (every part and
// every hole of it; a part too small for a curve keeps one cell). Homotopic thinning: border
// cells are peeled one layer at a time, from the north, east, south and west in turn, so the
// curves run down the middle; a cell goes only if it is simple (its removal neither splits nor
// joins anything, Yokoi's 8-connectivity number is 1) and not the end of a curve.
//
// Thread-safety: a value; const methods may be called from any number of threads.

#include <cstdint>
#include <vector>

#include "common/grid/cell_rect.hpp"
#include "common/route_graph/clearance_map.hpp"

namespace fleetmap::route_graph {

class Skeleton {
 public:
  Skeleton() = default;
  // The skeleton of the cells of `clearance` with a value >= `required`.
  Skeleton(const ClearanceMap& clearance, double required);

  // Sets the cells of `region` from `clearance` again and thins them, keeping every cell outside
  // `region` as it is: the new curves join the old ones where they cross the region's border.
  void Update(const ClearanceMap& clearance, double required, const grid::CellRect& region);

  int width() const { return width_; }
  int height() const { return height_; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  bool at(int x, int y) const { return Contains(x, y) && cells_[Index(x, y)] != 0; }

 private:
  size_t Index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
  void Thin(const grid::CellRect& region);
  bool Deletable(int x, int y) const;

  int width_ = 0;
  int height_ = 0;
  std::vector<uint8_t> cells_;
};

}  // namespace fleetmap::route_graph
