#pragma once

// What the local map says about the room behind a closed door, before any kernel: which cells of a
// window of the map's lattice the room may hold, and which of a candidate region are reachable
// from the doorway (docs/extrapolation.md, "Clipping behind a door"). The robot saw the room's
// surroundings, not the room: the corridor, the neighbouring rooms, the faces of the walls it
// stood next to. Four rules follow from that:
// - observed space is not the room: no cell the map shows free (another place) or occupied;
// - walls are thick: an unknown cell within `unseen_wall_thickness` behind a seen wall face
//   (along the face's normal, away from the free side) is wall, not room;
// - walls go on: a straight seen face at least `min_continued_wall` long is continued, along its
//   line, through unknown space (the corridor's end wall becomes the end room's side wall, a
//   neighbour's back wall the hidden room's back wall), unless the continuation meets observed
//   free space within `continuation_gap` (an opening, not a wall) or crosses the doorway;
// - a gap narrower than a person is not a way through: a face with a gap of fewer cells than
//   `min_passage_width` is treated as whole, and the region is cut at passages narrower than
//   `min_passage_width` (an opening by reconstruction with a disc of half that width: the
//   disc's positions followed from the doorway, the doorway itself always kept).
// Faces and continuations follow the grid's axes (floor plans and most indoor maps are drawn that
// way); walls at an angle to the grid are still stopped by their seen cells and thickness, but
// not continued.
//
// Thread-safety: immutable after construction.

#include <cstdint>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

// A window of a grid's cell lattice; it may extend beyond the grid (cells outside are unknown).
struct CellWindow {
  int x0 = 0;
  int y0 = 0;
  int width = 0;
  int height = 0;
};

struct DoorSpaceOptions {
  // Metres behind a seen wall face that are taken as wall (real walls are 0.15-0.5 m thick and a
  // laser sees one face).
  double unseen_wall_thickness = 0.3;
  // Passages (and gaps in a seen face) narrower than this lead nowhere (metres; a person's
  // shoulders).
  double min_passage_width = 0.5;
  // Seen faces at least this long are continued (metres; longer than any wall is thick, so the
  // jambs of a doorway are not continued into the room).
  double min_continued_wall = 0.6;
  // A continuation that meets observed free space within this distance of its face's end is an
  // opening, and is dropped (metres; two walls' thickness).
  double continuation_gap = 0.6;
  // No cell closer than this to the door line (metres): the wall the door sits in.
  double wall_clearance = 0.15;
};

class DoorSpace {
 public:
  // `opening` is the unit normal of the door into the unseen side.
  DoorSpace(const grid::OccupancyGrid& map, const scene::DoorEntity& door, const Vector2& opening,
            const CellWindow& window, const DoorSpaceOptions& options);

  // Per cell of the window (row-major): 1 where the room may be.
  const std::vector<uint8_t>& allowed() const { return allowed_; }

  // The cells of `candidate` (window-sized, row-major; callers pass a subset of allowed()) that
  // are 4-connected to the doorway through passages at least min_passage_width wide.
  std::vector<uint8_t> ReachableFromDoorway(const std::vector<uint8_t>& candidate) const;

  // The cells of `mask` (window-sized, row-major) 4-connected to the doorway, with no passage
  // width required: for bounds cut after ReachableFromDoorway.
  std::vector<uint8_t> ConnectedToDoorway(const std::vector<uint8_t>& mask) const;

  // Cells of the window just behind the doorway, where the flood starts (row-major indices).
  const std::vector<int>& seeds() const { return seeds_; }

 private:
  const grid::OccupancyGrid& map_;
  scene::DoorEntity door_;
  Vector2 opening_;
  CellWindow window_;
  DoorSpaceOptions options_;
  std::vector<uint8_t> allowed_;
  std::vector<uint8_t> doorway_;  // the opening through the door's wall (always passable)
  std::vector<int> seeds_;
};

}  // namespace fleetmap::extrapolation
