#pragma once

// People walking in an indoor scene, and what a robot sees of them (docs/extrapolation.md,
// "Indoor scenes"). A walk follows the corridor, keeping nearer to the wall on the person's
// dominant side, and may turn into a room through an open door. The robot observes a walk while the
// person is within range and in line of sight on the ground truth: the first stretch it sees
// becomes a track, flagged as entering or leaving the view when the walk goes on before or after
// it.
//
// Thread-safety: stateless; randomness from the caller's Random.

#include <optional>
#include <string>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/indoor_scene.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::sim {

struct WalkSample {
  double stamp = 0.0;  // seconds
  Point2 position = Point2::Zero();
  double heading = 0.0;
};

struct PersonWalk {
  std::string id;
  std::vector<WalkSample> samples;  // every `period` seconds
  int dominant_side = 1;            // -1 left, +1 right
};

struct WalkOptions {
  double period = 0.2;  // seconds between samples
  double min_speed = 1.0;
  double max_speed = 1.4;
  double min_length = 5.0;  // metres along the corridor
  double max_length = 9.0;
  double turn_in_probability = 0.4;  // turn into an open door ahead, if any
};

// `count` walks in the scene's corridor; `truth` (the ground floor, doors as set) keeps a walk
// into a room off the furniture.
std::vector<PersonWalk> GenerateWalks(const IndoorScene& scene, const grid::OccupancyGrid& truth,
                                      int count, const WalkOptions& options, Random* random);

struct ObservedWalk {
  std::string id;
  std::vector<WalkSample> points;  // with position and heading noise
  bool entered_view = false;
  bool left_view = false;
  int dominant_side = 1;  // the truth, for scoring
};

// The first stretch of at least two samples the robot at `robot` sees (within `range`, in line of
// sight on `truth`), or nothing.
std::optional<ObservedWalk> ObserveWalk(const PersonWalk& walk, const grid::OccupancyGrid& truth,
                                        const Point2& robot, double range, double position_noise,
                                        Random* random);

}  // namespace fleetmap::sim
