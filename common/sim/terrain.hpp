#pragma once

// A simulated world: the exact geometry of its obstacles, in metres, in the map frame. The terrain
// covers the square [0, size] x [0, size]; a boundary wall runs along its edge, so every point of
// the square is either inside an obstacle or free space the robot could in principle see.
//
// Designed to grow: every obstacle carries a kind and a `movable` flag, and doors are kept as
// their own entries (the doorway's segment and whether it is open), so movable objects, doors that
// open and close, stairs or people can be added as new kinds whose state changes over time without
// changing how the terrain is rasterized or exported.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::sim {

enum class TerrainKind : uint8_t { kMaze, kOffice, kUnstructured, kWarehouse };

// "maze", "office", "unstructured", "warehouse".
std::string_view TerrainKindName(TerrainKind kind);
std::optional<TerrainKind> TerrainKindFromName(std::string_view name);

enum class ObstacleKind : uint8_t {
  kBoundary,   // the terrain's outer wall
  kWall,       // an interior wall (straight, diagonal, or one piece of a curved wall)
  kFurniture,  // tables, cabinets (office)
  kRubble,     // irregular blobs (unstructured)
};
std::string_view ObstacleKindName(ObstacleKind kind);

// A wall: the segment a-b thickened by `thickness` (a capsule: every point within thickness / 2 of
// the segment is inside).
struct Wall {
  Point2 a = Point2::Zero();
  Point2 b = Point2::Zero();
  double thickness = 0.15;
  ObstacleKind kind = ObstacleKind::kWall;
  bool movable = false;
};

// A solid simple polygon (counter-clockwise or clockwise, not repeated at the end).
struct SolidPolygon {
  std::vector<Point2> points;
  ObstacleKind kind = ObstacleKind::kFurniture;
  bool movable = false;
};

// A doorway in a wall: the gap between a and b. Open doors leave the gap free.
struct Door {
  Point2 a = Point2::Zero();
  Point2 b = Point2::Zero();
  bool open = true;
  double thickness = 0.15;  // of the wall it sits in; a closed door fills the gap like a wall
};

struct Terrain {
  TerrainKind kind = TerrainKind::kOffice;
  double size = 10.0;  // metres, side of the square
  uint32_t seed = 0;
  std::vector<Wall> walls;
  std::vector<SolidPolygon> polygons;
  std::vector<Door> doors;
  // Where a robot can start: free, away from every obstacle.
  Pose2 start;
};

}  // namespace fleetmap::sim
