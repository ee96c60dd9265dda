#pragma once

// The occupied cells of a fleet-frame grid (rt/fleetmap/map), as fleet-frame cell keys: what
// integration tests compare across maps whose windows differ.

#include <cmath>
#include <set>
#include <utility>

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::testing {

inline std::set<std::pair<int, int>> OccupiedCells(const grid::OccupancyGrid& grid) {
  std::set<std::pair<int, int>> cells;
  const int ox = static_cast<int>(std::lround(grid.origin().x / grid.resolution()));
  const int oy = static_cast<int>(std::lround(grid.origin().y / grid.resolution()));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.at(x, y) >= 65) cells.emplace(ox + x, oy + y);
    }
  }
  return cells;
}

}  // namespace fleetmap::testing
