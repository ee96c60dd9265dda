#pragma once

// Predicted sub-maps brought back onto the local map's floor, for files and pictures: a sub-map's
// grid with its origin in the map frame, and one grid that covers the local map and every
// predicted sub-map on the same floor.
//
// Thread-safety: stateless.

#include "common/extrapolation/extrapolator.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::extrapolation {

// `submap.navigable` with its origin expressed in the map frame.
grid::OccupancyGrid SubmapGridInMapFrame(const scene::Submap& submap);

struct FloorGrids {
  // The local map's lattice, grown to cover the door sub-maps: 0 where the extrapolation predicts
  // free space the local map did not show free (doors and people), -1 elsewhere.
  grid::OccupancyGrid predicted_free;
  // The same geometry: the local map, with the predicted free cells added.
  grid::OccupancyGrid extrapolated;
  int64_t predicted_free_cells = 0;
  int64_t observed_free_cells = 0;
};

// Stairs sub-maps (another floor) are left out. The local map's origin must be axis-aligned
// with the sub-maps' lattices (Extrapolate guarantees it).
FloorGrids ComposeFloorGrids(const grid::OccupancyGrid& local_map,
                             const ExtrapolationResult& result);

}  // namespace fleetmap::extrapolation
