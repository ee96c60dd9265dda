#pragma once

// Occupancy grids carried between frames by a rigid transform, by nearest-neighbour reads: how a
// simulated robot whose SLAM map frame is the world frame moved (fleetmap sim --unknown-poses)
// gets its map in its own frame, and how a map in one robot's frame is scored against the
// world-frame ground truth. A second SLAM run rasterizing the same walls in another frame would
// make the same kind of grid: every cell is one cell of the source, never a blend.

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::sim {

// Fills every cell of `*target` with the value of the `source` cell under its centre; cells whose
// centre falls off `source` become unknown. `source_from_target` takes target-frame points to the
// source's frame. Either grid's origin may be rotated.
void ResampleRigid(const grid::OccupancyGrid& source, const Transform2& source_from_target,
                   grid::OccupancyGrid* target);

// `source` carried into another frame (`to_from_source` takes source-frame points there): an
// axis-aligned grid of the same resolution whose corners lie on whole multiples of the resolution
// in that frame (so the same source geometry always gives the same lattice), just large enough to
// hold the source's cells.
grid::OccupancyGrid ResampleIntoFrame(const grid::OccupancyGrid& source,
                                      const Transform2& to_from_source);

}  // namespace fleetmap::sim
