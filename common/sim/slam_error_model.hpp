#pragma once

// How far the pose a SLAM system believes is from the truth, so that simulated robot maps look
// like real SLAM output (docs/simulator.md, "Error model"). The belief is the true pose plus an
// offset (dx, dy, dyaw) with two parts:
//  - drift: a random walk in the distance travelled (standard deviation drift_* per sqrt(metre)),
//    pulled back towards zero with the length scale `correction_length` (an Ornstein-Uhlenbeck
//    process): scan matching and loop closures keep a real SLAM's error bounded, so the drift
//    neither vanishes nor grows without limit (its steady-state deviation is
//    drift * sqrt(correction_length / 2));
//  - jitter: independent Gaussian noise on every scan's pose (scan-matching noise), which blurs
//    walls over one or two cells.
// Disabled, the belief is the truth.
//
// Thread-safety: not thread-safe; one owner.

#include <cstdint>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::sim {

struct SlamErrorOptions {
  bool enabled = true;
  double jitter_xy = 0.01;          // metres, per scan, >= 0
  double jitter_yaw = 0.002;        // radians, per scan, >= 0
  double drift_xy = 0.005;          // metres per sqrt(metre travelled), >= 0
  double drift_yaw = 0.0005;        // radians per sqrt(metre travelled), >= 0
  double correction_length = 10.0;  // metres; <= 0 turns corrections off (pure random walk)
};

class SlamErrorModel {
 public:
  // Errors (kInvalidArgument) name the option: negative or non-finite deviations.
  static StatusOr<SlamErrorModel> Create(const SlamErrorOptions& options, uint32_t seed);

  // The robot moved `distance` metres (translation plus rotation times a 0.3 m lever arm).
  void Advance(double distance);
  // The pose the SLAM believes for the current scan, given the true pose (draws fresh jitter).
  Pose2 Belief(const Pose2& truth);
  // The current drift offset (x, y in metres, yaw in radians), without jitter.
  const Pose2& drift() const { return drift_; }

 private:
  SlamErrorModel(const SlamErrorOptions& options, uint32_t seed)
      : options_(options), random_(seed) {}

  SlamErrorOptions options_;
  Random random_;
  Pose2 drift_;
};

}  // namespace fleetmap::sim
