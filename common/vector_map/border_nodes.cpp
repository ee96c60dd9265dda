#include "common/vector_map/border_nodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fleetmap::vector_map {

bool BorderNodes::Occupied(int x, int y) const {
  if (raster_.Contains(x, y)) return raster_.Has(raster_.Index(x, y), CellRaster::kOccupied);
  if (!grid_.Contains(x, y)) return false;
  return grid::StateOf(grid_.at(x, y), thresholds_) == grid::CellState::kOccupied;
}

// `out` is the unit step across the border, `along` the unit step along it.
std::optional<Point2> BorderNodes::Node(int x, int y, int out_x, int out_y) const {
  const int along_x = out_y != 0 ? 1 : 0;
  const int along_y = out_x != 0 ? 1 : 0;
  auto crossing_at = [&](int t) {
    const int ix = x + t * along_x;
    const int iy = y + t * along_y;
    return Occupied(ix, iy) && Occupied(ix + out_x, iy + out_y);
  };
  int t0 = 0;
  bool found = crossing_at(0);
  if (!found && crossing_at(-1)) {
    t0 = -1;
    found = true;
  } else if (!found && crossing_at(1)) {
    t0 = 1;
    found = true;
  }
  const Point2 inner(x, y);
  const Point2 half_out(0.5 * out_x, 0.5 * out_y);
  const Point2 along(along_x, along_y);
  if (!found) {
    // Only a diagonal anchor: end at the cell corner shared with it.
    for (const int t : {-1, 1}) {
      if (Occupied(x + t * along_x + out_x, y + t * along_y + out_y)) {
        return inner + half_out + 0.5 * t * along;
      }
    }
    return std::nullopt;
  }
  int lo = t0;
  int hi = t0;
  const int limit = std::max(grid_.width(), grid_.height());
  while (lo - 1 > -limit && crossing_at(lo - 1)) --lo;
  while (hi + 1 < limit && crossing_at(hi + 1)) ++hi;
  const int length = hi - lo + 1;
  if (length <= 3) return inner + half_out + 0.5 * (lo + hi) * along;
  const Point2 first = inner + half_out + (lo + 0.5) * along;
  const Point2 last = inner + half_out + (hi - 0.5) * along;
  return std::abs(lo + 0.5) <= std::abs(hi - 0.5) ? first : last;
}

std::optional<Point2> BorderNodes::For(int index, int next) const {
  const CellRect& rect = raster_.rect();
  const int x = raster_.X(index);
  const int y = raster_.Y(index);
  struct Side {
    bool at;
    int out_x;
    int out_y;
  };
  const std::array<Side, 4> sides = {{{x == rect.x0, -1, 0},
                                      {x == rect.x0 + rect.width - 1, 1, 0},
                                      {y == rect.y0, 0, -1},
                                      {y == rect.y0 + rect.height - 1, 0, 1}}};
  for (const Side& side : sides) {
    if (!side.at) continue;
    if (next < 0) continue;
    // The chain must come from inside: its next pixel one step farther from this side.
    const int step_out = (raster_.X(next) - x) * side.out_x + (raster_.Y(next) - y) * side.out_y;
    if (step_out >= 0) continue;
    const int along_x = side.out_y != 0 ? 1 : 0;
    const int along_y = side.out_x != 0 ? 1 : 0;
    bool anchored = false;
    for (int t = -1; t <= 1; ++t) {
      const int ax = x + side.out_x + t * along_x;
      const int ay = y + side.out_y + t * along_y;
      if (raster_.Has(raster_.Index(ax, ay), CellRaster::kAnchor)) anchored = true;
    }
    if (!anchored) continue;
    if (auto node = Node(x, y, side.out_x, side.out_y)) return node;
  }
  return std::nullopt;
}

}  // namespace fleetmap::vector_map
