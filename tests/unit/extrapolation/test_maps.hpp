#pragma once

// Small indoor grids and doors for the extrapolation tests: a corridor with a door in its upper
// wall, and two rooms above it seen through doorways.

#include <cstdint>
#include <string>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation::testing {

inline constexpr double kRes = 0.05;

// Sets every cell whose centre lies in [x0, x1) x [y0, y1) to `value`.
inline void Fill(grid::OccupancyGrid* map, double x0, double y0, double x1, double y1,
                 int8_t value) {
  for (int y = 0; y < map->height(); ++y) {
    for (int x = 0; x < map->width(); ++x) {
      const Point2 c = map->CellCenter(x, y);
      if (c.x() >= x0 && c.x() < x1 && c.y() >= y0 && c.y() < y1) map->at(x, y) = value;
    }
  }
}

// 10 x 8 m: a corridor y in [0.15, 2] the robot has seen, walls below it and above it (y in
// [2, 2.15]) with a closed door between x = 4 and 5; above the wall nothing is known.
inline grid::OccupancyGrid Corridor() {
  grid::OccupancyGrid map(200, 160, kRes);
  Fill(&map, 0, 0, 10, 0.15, grid::kOccupiedValue);
  Fill(&map, 0, 0.15, 10, 2.0, grid::kFreeValue);
  Fill(&map, 0, 2.0, 10, 2.15, grid::kOccupiedValue);
  return map;
}

// Corridor() with two rooms above it, y in [2.15, 6], split at x = 4.9 by a wall, each seen
// through a doorway in the corridor's wall: x in [2, 3] and [6, 7].
inline grid::OccupancyGrid CorridorWithRooms() {
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 0, 2.15, 10, 6.0, grid::kFreeValue);
  Fill(&map, 4.9, 2.15, 5.05, 6.0, grid::kOccupiedValue);
  Fill(&map, 0, 6.0, 10, 6.15, grid::kOccupiedValue);
  Fill(&map, 2.0, 2.0, 3.0, 2.15, grid::kFreeValue);
  Fill(&map, 6.0, 2.0, 7.0, 2.15, grid::kFreeValue);
  return map;
}

// A door in the corridor's upper wall line y, opening into +y (the side not seen).
inline scene::DoorEntity DoorAt(const std::string& id, double x0, double x1, double y, bool open) {
  scene::DoorEntity door;
  door.id = id;
  door.hinge = Point2(x0, y);
  door.latch = Point2(x1, y);
  door.opening_direction = Vector2(0, 1);
  door.open = open;
  return door;
}

}  // namespace fleetmap::extrapolation::testing
