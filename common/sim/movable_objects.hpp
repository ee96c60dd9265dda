#pragma once

// Movable objects for the simulator (issue 6): chairs, bins and boxes that stand in a terrain and
// move between mapping sessions. Each shape looks different on a 5 cm grid:
//  - chair: an L (two 0.55 m arms, 0.15 m thick; seat and back seen from above),
//  - bin: a circle of radius 0.2 m (a 20-gon),
//  - box: a 0.7 x 0.4 m rectangle.
// An object is a SolidPolygon of kind furniture with movable = true, so terrains with objects
// rasterize, export and get mapped like any other terrain.
//
// Thread-safety: stateless.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "common/core/types.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

enum class MovableShape : uint8_t { kChair, kBin, kBox };

// "chair", "bin", "box".
std::string_view MovableShapeName(MovableShape shape);
std::optional<MovableShape> MovableShapeFromName(std::string_view name);

// One object in one session: its shape and where it stands (centre of its bounding disc, heading).
struct MovableObject {
  int id = 0;  // which physical object (stable across sessions)
  MovableShape shape = MovableShape::kChair;
  Pose2 pose;
};

// Radius of the disc (about the pose) that contains the shape, metres.
double MovableShapeRadius(MovableShape shape);

// The object's footprint in the map frame (kind furniture, movable).
SolidPolygon MovableObjectPolygon(const MovableObject& object);

// `base` with the objects added as movable polygons (everything else unchanged).
Terrain WithMovableObjects(const Terrain& base, const std::vector<MovableObject>& objects);

}  // namespace fleetmap::sim
