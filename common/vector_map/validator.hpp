#pragma once

// Checks a vector map against the grid it claims to represent (ALGORITHMS.md 1):
//  - epsilon-error: every delimitation point p within epsilon of some edge. Exact: each edge visits
//    the cells of a band around it and computes exact point-segment distances.
//  - continuity: every point of every edge within epsilon of some delimitation point. Decided
//    exactly per edge (SegmentContinuous: the union of the epsilon-discs of the delimitation points
//    near the edge, intersected with the edge, must cover it).
// Both use a relative slack of 1e-9 (segment_geometry.hpp). Reported worst distances are
// informative: the point distance is exact up to a search radius of 2 * epsilon + 2 cells (beyond,
// it is clamped there); the segment distance is sampled every 0.1 cell, so the true maximum lies
// within 0.05 cell above it.
//
// Thread-safety: stateless; concurrent calls are safe.

#include <cstdint>
#include <optional>
#include <utility>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/delimitation.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

struct ValidatorOptions {
  grid::StateThresholds thresholds;
  // Metres; <= 0 takes the map's own epsilon.
  double epsilon = 0.0;
  // Only delimitation points inside this rectangle must be covered (checking one tile).
  std::optional<CellRect> rect;
  // Compute the sampled worst segment distance (costs about 20 samples per cell of edge length).
  bool measure_segment_distance = true;
};

struct ValidationReport {
  int64_t delimitation_points = 0;
  int64_t uncovered_points = 0;         // epsilon-error violations
  double worst_point_distance = 0.0;    // metres
  int64_t segments = 0;                 // including zero-length ones (point obstacles)
  int64_t discontinuous_segments = 0;   // continuity violations
  double worst_segment_distance = 0.0;  // metres

  bool ok() const { return uncovered_points == 0 && discontinuous_segments == 0; }
};

class Validator {
 public:
  explicit Validator(ValidatorOptions options = {}) : options_(std::move(options)) {}

  // The map is read in the grid's frame (its vertices are map-frame metres). Errors: a grid with
  // a bad resolution or a non-positive epsilon.
  StatusOr<ValidationReport> Validate(const VectorMap& map,
                                      const grid::OccupancyGrid& source) const;

 private:
  ValidatorOptions options_;
};

}  // namespace fleetmap::vector_map
