#pragma once

// Seeded indoor scenes for the map-extrapolation benchmark (docs/extrapolation.md,
// "Indoor scenes"): a corridor running east with offices on both sides (3-5.5 m wide, 4-5.5 m deep,
// each with a 0.85-1 m door on the corridor, the hinge on either side, 0-3 pieces of furniture kept
// 1.3 m from the door), a straight flight of stairs filling the corridor's east end, and on the
// floor above a hall beyond the top of the flight (0-1.5 m wider than the flight each side, 1.5-4.5
// m long, 0-2 benches kept 1 m from the top edge). Same options and seed -> the same scene.
//
// Thread-safety: stateless.

#include <cstdint>

#include "common/sim/indoor_scene.hpp"

namespace fleetmap::sim {

struct IndoorSceneOptions {
  double closed_door_probability = 0.5;  // each door, in [0, 1]
  double corridor_length = 14.0;         // metres from the west wall to the foot of the stairs
  double wall_thickness = 0.12;
  double wall_height = 2.6;
  double floor_height = 3.0;  // nominal; each scene varies it by up to +-0.1 m
};

IndoorScene GenerateIndoorScene(const IndoorSceneOptions& options, uint32_t seed);

}  // namespace fleetmap::sim
