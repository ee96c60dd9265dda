#pragma once

// How far a fused map agrees with a robot's map: what the fleet tests check a fused grid by.

#include <cstdint>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::testing {

// Share of the known cells of `source` (its map frame, carried into the fleet frame by
// `fleet_from_source`) that `fused` (fleet frame) gives the same state.
inline double Agreement(const grid::OccupancyGrid& source, const Transform2& fleet_from_source,
                        const grid::OccupancyGrid& fused) {
  int64_t known = 0, same = 0;
  for (int y = 0; y < source.height(); ++y) {
    for (int x = 0; x < source.width(); ++x) {
      const grid::CellState state = source.StateAt(x, y);
      if (state == grid::CellState::kUnknown) continue;
      ++known;
      const auto cell = fused.CellAt(fleet_from_source * source.CellCenter(x, y));
      if (cell && fused.StateAt(cell->x, cell->y) == state) ++same;
    }
  }
  return known == 0 ? 0.0 : static_cast<double>(same) / known;
}

}  // namespace fleetmap::testing
