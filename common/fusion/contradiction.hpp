#pragma once

#include <cstdint>
#include <vector>

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::fusion {

// One robot's cells of one fused tile, weighed against what the rest of the fleet established
// there. The rule (docs/fleet.md, "Quarantine") is registration's verification turned around:
// an established occupied cell is contradicted when the robot calls it free, its evidence for the
// cell is newer than the fleet's (older evidence never erases anything: newer wins), it has no
// occupied cell within the tolerance (two honest maps of one wall differ by noise and drift), its
// free space breaches the wall there (free through the wall's whole thickness: scans grazing a
// wall clear its near face only), and no robot of another participant has seen the cell free since
// the fleet's evidence (a door that opened, a shelf that moved: a change two robots see is a
// change, not a contradiction).
struct TileContradiction {
  int64_t established_seen = 0;  // established occupied cells the robot knows (free or occupied)
  int64_t contradicted = 0;      // of those, the ones it contradicts
  // The contradicted cells' bounding box on the tile's cells; empty (width 0) when none.
  int min_x = 0, min_y = 0, max_x = -1, max_y = -1;
  // Its occupied cells that robots of other participants know (free or occupied), and of those
  // the ones they confirm: an occupied cell of theirs within the tolerance (CountAgreement).
  int64_t walls_known = 0;
  int64_t walls_confirmed = 0;

  bool any() const { return contradicted > 0; }
};

// What the rest of the fleet says about a tile's cells.
struct EstablishedCells {
  const grid::OccupancyGrid* cells = nullptr;    // 3-state, fused from the trusted others
  const std::vector<uint32_t>* dates = nullptr;  // per cell: the evidence date of that state
  // Per cell: the newest date a robot of another participant saw it free (empty: nobody did).
  const std::vector<uint32_t>* confirmed_free_at = nullptr;
};

// Counts `robot_cells` (3-state, dated per cell by `robot_dates`) against `established`, on one
// lattice of the same size. `tolerance_cells` >= 0.
TileContradiction CountContradiction(const grid::OccupancyGrid& robot_cells,
                                     const std::vector<uint32_t>& robot_dates,
                                     const EstablishedCells& established, int tolerance_cells);

// Fills `counted`'s walls_known and walls_confirmed: `robot_cells`' occupied cells that `others`
// (3-state, robots of other participants only) know, and those with an occupied cell of
// `others` within `tolerance_cells`. Same lattice.
void CountAgreement(const grid::OccupancyGrid& robot_cells, const grid::OccupancyGrid& others,
                    int tolerance_cells, TileContradiction* counted);

}  // namespace fleetmap::fusion
