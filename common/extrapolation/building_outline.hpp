#pragma once

// What the local map says about the building a hidden room belongs to (docs/extrapolation.md,
// "The building's outline"): its principal directions, its observed outer walls, and the lines
// those walls continue along. A room behind a closed door is inside the building, so:
// - a prediction never crosses the continuation of an observed outer wall: a straight seen wall
//   face at least `min_outer_wall` long with no observed free space anywhere behind it, continued
//   along its line through unknown and occupied cells across the whole map until it meets observed
//   free space (dropped if that happens within `continuation_gap` of its end: an opening);
// - a prediction never lands outside the outline: beyond the outermost observed outer wall in
//   each of the four principal directions (a direction where free space was seen beyond every
//   wall, a scan through a window, is not bounded).
// Unlike DoorSpace, which looks at the few metres around a door along the grid's axes, this looks
// at the whole map, along the building's principal directions (the angle, modulo 90 degrees, at
// which the seen wall faces line up best), so a wall seen three rooms away still bounds the room,
// and a building drawn at an angle to the grid is handled.
//
// Thread-safety: immutable after construction.

#include <cstdint>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

struct BuildingOutlineOptions {
  // Metres: a seen face at least this long can be an outer wall (a wall, not a jamb or furniture).
  double min_outer_wall = 1.0;
  // Metres: gaps in a seen face narrower than this (laser dropouts) count as face.
  double max_face_gap = 0.5;
  // Metres: a continuation that meets observed free space this close to its wall's end is an
  // opening, and is dropped.
  double continuation_gap = 0.6;
  // Share of a face's cells with no observed free space behind them for it to be an outer wall.
  double min_outer_share = 0.8;
};

class BuildingOutline {
 public:
  BuildingOutline(const grid::OccupancyGrid& map, const BuildingOutlineOptions& options);

  // Radians in [0, pi/2): the building's principal directions are this angle and a right angle
  // more, in the map's lattice.
  double principal_angle() const { return angle_; }
  // Observed outer walls found (each continued along its line).
  int outer_walls() const { return static_cast<int>(lines_.size()); }

  // Per map cell (row-major): 1 where a room behind `door` may be, 0 where the building's outline
  // or an outer wall's continuation excludes it. Continuations that pass through the doorway less
  // than 1 m behind the door line, and bounds the doorway lies beyond, are the door's own wall,
  // not the room's outline, and are not applied. `opening`: the door's unit normal into the room.
  std::vector<uint8_t> AllowedFor(const scene::DoorEntity& door, const Vector2& opening) const;

 private:
  // A continued outer wall in the rotated lattice: on `line` (a row when `along_u`, else a
  // column), barrier from `lo` to `hi` (inclusive, rotated cells), the building on the side
  // opposite `outward` (+1 / -1 along the other axis).
  struct Line {
    bool along_u = true;
    int line = 0;
    int lo = 0;
    int hi = 0;
    int outward = 1;
  };

  // Rotated lattice cell of a map lattice point (cell units).
  void ToRotated(double qx, double qy, int* i, int* j) const;

  const grid::OccupancyGrid& map_;
  double angle_ = 0.0;
  double cos_ = 1.0, sin_ = 0.0;
  double u0_ = 0.0, v0_ = 0.0;  // rotated coordinates of the rotated grid's corner
  int width_ = 0, height_ = 0;  // rotated grid size (cells)
  std::vector<Line> lines_;
  // Outline: the building is at rotated u in [min_u_, max_u_] and v in [min_v_, max_v_] (cells);
  // unbounded directions hold the int limits.
  int min_u_ = 0, max_u_ = 0, min_v_ = 0, max_v_ = 0;
};

}  // namespace fleetmap::extrapolation
