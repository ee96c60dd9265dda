#pragma once

// An indoor scene for the map-extrapolation benchmark (docs/extrapolation.md, "Indoor scenes"): one
// floor of offices along a corridor, doors that are open or closed (with leaves and handles),
// a flight of stairs at the end of the corridor up to a hall on the floor above, in exact 2D
// geometry (a Terrain, so the usual rasterizer gives its ground truth) and as upright 3D boxes
// for the depth sensor.
//
// Frames: the map frame of the ground floor; z up, the ground floor at z = 0, the upper floor at
// z = stairs.height().
//
// Thread-safety: plain data; the functions are stateless.

#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

// An upright box: a rectangle (centre, yaw, half extents) extruded from z_min to z_max.
struct Box3 {
  Point2 center = Point2::Zero();
  double yaw = 0.0;
  double half_length = 0.0;  // along yaw
  double half_width = 0.0;   // across
  double z_min = 0.0;
  double z_max = 0.0;
};

// A door in a corridor wall. `room_side` is the unit normal pointing into the room (away from the
// corridor); an open leaf stands in the room, turned 90 degrees about the hinge.
struct SceneDoor {
  Point2 hinge = Point2::Zero();
  Point2 latch = Point2::Zero();
  Vector2 room_side = Vector2::UnitY();
  double height = 2.05;
  double leaf_thickness = 0.04;
  double wall_thickness = 0.12;
  bool open = false;

  double width() const { return (latch - hinge).norm(); }
  Point2 center() const { return 0.5 * (hinge + latch); }
};

// A straight flight: `risers` steps of `rise` and `tread`; riser k stands at k * tread along
// `ascending` from `foot` (the middle of the first riser, on the floor); the last riser brings
// the walker onto the upper floor, whose edge (the top of the flight) is at run() from the foot.
struct SceneStairs {
  Point2 foot = Point2::Zero();
  Vector2 ascending = Vector2::UnitX();
  double width = 1.5;
  double rise = 0.17;
  double tread = 0.28;
  int risers = 18;
  // The solid block under the upper floor's edge (a landing / storage), along `ascending`.
  double block_length = 3.0;

  double height() const { return rise * risers; }
  double run() const { return tread * (risers - 1); }
  Point2 top() const { return foot + run() * ascending; }
};

struct IndoorScene {
  // The ground floor: walls, furniture (polygons, movable), the stairs' footprint (a polygon),
  // and the doors (same order as `doors`; Door::open mirrors SceneDoor::open). A filler polygon
  // covers the part of the square outside the building.
  Terrain ground;
  std::vector<SceneDoor> doors;
  std::vector<double> polygon_heights;  // per ground.polygons, metres
  SceneStairs stairs;
  // The floor above, around the top of the stairs: a hall [hall_min, hall_max] (map frame) with
  // walls and furniture; everything else up there reads as occupied in its ground truth.
  Terrain upper;
  Point2 hall_min = Point2::Zero();
  Point2 hall_max = Point2::Zero();
  double wall_height = 2.6;
  // The corridor's clear band (between the wall faces), up to the foot of the stairs.
  Point2 corridor_min = Point2::Zero();
  Point2 corridor_max = Point2::Zero();
};

// The scene's ground floor as 3D boxes: walls, lintels, door leaves and handles, furniture,
// steps and the block under the landing. (The floor itself is the plane z = 0.)
std::vector<Box3> SceneBoxes(const IndoorScene& scene);

// The ground floor's ground truth (RasterizeTerrain): with the doors as they are
// (`doors_as_set` = true; closed doors fill their gap) or all open (the true layout of the rooms).
StatusOr<grid::OccupancyGrid> RasterizeGroundFloor(const IndoorScene& scene, double resolution,
                                                   bool doors_as_set);

// The upper floor's ground truth on the same lattice: free inside the hall and off its furniture,
// occupied elsewhere (walls, the stairwell, rooms not modelled).
StatusOr<grid::OccupancyGrid> RasterizeUpperFloor(const IndoorScene& scene, double resolution);

}  // namespace fleetmap::sim
