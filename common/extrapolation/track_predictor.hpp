#pragma once

// Linear short-horizon prediction of a person's track (ALGORITHMS.md 3, humans): a_h(t + k) =
// a_h(t) + k a_h'(t), forward from the last pose when the person left the view, backward from the
// first when they entered it. The velocity is a least-squares fit over the last (first) second.
// The result is resampled at even spacing, so the personal-space kernel sweeps a continuous band.
//
// Thread-safety: stateless.

#include <vector>

#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

struct TrackPredictorOptions {
  double horizon = 0.8;         // seconds predicted beyond the observed end(s)
  double fit_window = 1.0;      // seconds of track the velocity is fitted on
  double sample_spacing = 0.1;  // metres between output poses
  double max_speed = 3.0;       // m/s: a faster fit is cut to this (tracking glitches)
};

struct SweptPose {
  Point2 position = Point2::Zero();
  double heading = 0;
  bool predicted = false;  // beyond the observed track
};

// The track (>= 2 points, stamps increasing) densified to `sample_spacing`, plus the predicted
// parts. Headings of predicted poses follow the fitted velocity; if the person stands still,
// nothing is predicted.
std::vector<SweptPose> SweepTrack(const scene::PersonTrack& track,
                                  const TrackPredictorOptions& options);

}  // namespace fleetmap::extrapolation
