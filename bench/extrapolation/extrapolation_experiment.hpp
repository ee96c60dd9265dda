#pragma once

// The map-extrapolation experiment (ALGORITHMS.md 3, "The paper's results"; docs/extrapolation.md,
// "Benchmark") on one simulated indoor scene: a robot drives part of the corridor with a short
// range 360-degree laser and maps it; an RGB-D camera looks at every closed door it mapped and at
// the stairs; people walk by. The detectors turn the camera's points into doors and stairs, the
// people's observed tracks come with the robot's perception, and the extrapolation predicts free
// space, which is scored against the ground truth: the rooms behind the doors (doors open), the
// hall on the floor above, the corridor and rooms the people walked in.
// `fleetmap bench extrapolation` runs it over many seeds and writes the report.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/extrapolation/prediction_check.hpp"

namespace fleetmap::bench {

inline constexpr int kMaxThresholds = 8;

struct ExtrapolationSceneOptions {
  uint32_t seed = 1;
  std::vector<double> p_th = {0.5, 0.6, 0.7};
  double resolution = 0.05;
  double closed_door_probability = 0.6;
  double laser_range = 4.5;  // metres: the local map is a short-range one
  double person_view_range = 4.0;
  int people = 4;
  int stairs_views = 2;
  extrapolation::ExtrapolationOptions extrapolation;  // its p_th is replaced by each of p_th
  // If set, the scene's inputs are written there for `fleetmap extrapolate`: local.yaml (+ .pgm),
  // entities.json (detected doors and stairs, observed tracks), truth.yaml (the floor, doors
  // open), upper.yaml (the floor above) and views.ply (the camera's points, all views).
  std::string example_dir;
};

// Scores per threshold: the free-space precision of each class and the surface gained.
struct ThresholdScores {
  extrapolation::PredictionCheck stairs;  // static: predicted hall vs the upper floor's truth
  extrapolation::PredictionCheck doors;   // quasi-static: new cells vs the rooms' truth
  extrapolation::PredictionCheck people;  // dynamic: new cells vs the floor's truth
  int64_t door_new_cells = 0;             // predicted free behind closed doors, unknown before
  int64_t people_new_cells = 0;
};

struct ExtrapolationSceneResult {
  uint32_t seed = 0;
  int closed_doors_viewed = 0;   // closed doors the robot mapped and looked at
  int doors_detected = 0;        // of those, found by the detector in their view
  int hinges_correct = 0;        // of those, with the hinge on the right side
  int door_false_positives = 0;  // detections matching no door of the scene
  int stairs_views = 0;
  int stairs_detected = 0;
  int stairs_false_positives = 0;
  int tracks = 0;  // people's tracks observed
  int dominant_sides_correct = 0;
  int64_t observed_free_cells = 0;
  double cell_area = 0.0;               // m^2
  std::vector<ThresholdScores> scores;  // one per p_th
};

// Errors: bad options (a simulator component refused them).
StatusOr<ExtrapolationSceneResult> RunExtrapolationScene(const ExtrapolationSceneOptions& options);

}  // namespace fleetmap::bench
