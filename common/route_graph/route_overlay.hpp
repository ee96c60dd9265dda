#pragma once

// What the route graph knows beyond the fused grid's cells (issue 37): free space the server
// predicts behind doors and up stairs that no robot has observed yet, and the cells learned
// movable objects (pallets, carts) occupy. A fleet manager wants edges through both, marked: an
// edge through predicted space is a plan that a robot must confirm on the way, an edge through a
// movable object is a plan that waits for the object to be moved. So the graph is built on the
// grid with these cells opened (RouteOverlay::Open) and each edge and node says which it crosses.
//
// Plain data laid on one grid's cells; made on the route graph worker's thread, read by the
// builder.

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/patch.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::route_graph {

// Free space predicted behind a closed door on this floor (a predicted sub-map: navigable cells
// free where free space is predicted), and the door: the cells of a door a robot saw shut are
// where a robot would pass into the predicted room, so they are predicted passable too.
struct PredictedSpace {
  scene::Submap submap;
  std::optional<std::array<Point2, 2>> door;  // hinge and latch, map frame
};

// A learned movable object (rt/fleetmap/objects): its occupancy patch and where it was seen, each
// the map-frame pose of the patch's centre.
struct MovableObject {
  uint32_t id = 0;
  scene::Patch patch;
  std::vector<Pose2> sightings;
};

class RouteOverlay {
 public:
  // A patch cell at or above this occupancy is part of the object's footprint.
  static constexpr float kObjectCell = 0.5F;

  RouteOverlay() = default;

  // The door's cells: within this distance of the door's line, between its jambs.
  static constexpr double kDoorDepth = 0.25;

  // The overlay on `grid`'s cells (yaw 0): the cells `grid` leaves unknown that a predicted
  // sub-map calls free, the cells of its door that are not free, and the cells `grid` calls
  // occupied that lie in an object's footprint at one of its sightings. Observed cells are never
  // predicted (but for a shut door's), and free cells never an object's: the grid wins.
  static RouteOverlay Make(const grid::OccupancyGrid& grid,
                           const std::vector<PredictedSpace>& predicted,
                           const std::vector<MovableObject>& objects,
                           const grid::StateThresholds& thresholds = {});

  bool empty() const { return predicted_.empty() && objects_.empty(); }
  size_t predicted_cells() const { return predicted_.size(); }
  size_t object_cells() const { return objects_.size(); }

  // Cell indices are the grid's (y * width + x).
  bool Predicted(int64_t cell) const;
  // The object whose footprint holds the cell, if any.
  std::optional<uint32_t> ObjectAt(int64_t cell) const;

  // `grid` with every cell of the overlay free: what the graph is built on.
  void Open(grid::OccupancyGrid* grid) const;
  // The cells in one overlay and not the other, or with another object: sorted cell indices.
  std::vector<int64_t> Differences(const RouteOverlay& other) const;

 private:
  std::vector<int64_t> predicted_;                     // sorted
  std::vector<std::pair<int64_t, uint32_t>> objects_;  // sorted by cell: (cell, object id)
};

}  // namespace fleetmap::route_graph
