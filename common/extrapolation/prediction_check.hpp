#pragma once

// Scores a prediction against a later (or ground-truth) observation of the same area: each
// predicted free cell's centre, taken to the map frame, is looked up in the observed grid.
//
// Thread-safety: stateless.

#include <cstdint>

#include "common/grid/occupancy_grid.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::extrapolation {

struct PredictionCheck {
  int64_t true_free = 0;         // predicted free, observed free
  int64_t false_free = 0;        // predicted free, observed occupied
  int64_t unobserved = 0;        // predicted free, observed unknown or outside the observed grid
  double precision = 0;          // true_free / (true_free + false_free); 0 if nothing was observed
  double observed_fraction = 0;  // (true_free + false_free) / predicted free cells; 0 if none

  PredictionCheck& operator+=(const PredictionCheck& other);  // sums counts, recomputes ratios
};

// `observed` is in the map frame with any geometry.
PredictionCheck CheckPrediction(const scene::Submap& predicted,
                                const grid::OccupancyGrid& observed);

// The same for a grid in the map frame (e.g. ExtrapolationResult::conditionally_free). Cells that
// `already_known` (if given, any geometry) shows free or occupied are not counted: only what the
// prediction added is scored.
PredictionCheck CheckPredictedGrid(const grid::OccupancyGrid& predicted,
                                   const grid::OccupancyGrid& observed,
                                   const grid::OccupancyGrid* already_known = nullptr);

}  // namespace fleetmap::extrapolation
