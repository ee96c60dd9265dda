#pragma once

// Map-quality metrics of seed 002, section 4, as ALGORITHMS.md 1.1 restates them. R (robot map) and
// G (ground truth) must have the same geometry. Cell values: occupied 1, free 0, unknown 0.5.
// Every score is a percentage; a score whose denominator is zero (no cells, a constant map, no
// occupied / free cell in R) is undefined (an empty optional), never 100.
//
// Thread-safety: stateless functions.

#include <optional>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::metrics {

struct QualityOptions {
  // OPDF / UPDF search window (cells): offsets |dx| <= window_width / 2, |dy| <= window_height / 2
  // (integer division); a cell with no match inside pays r = sqrt(w^2 + h^2).
  int window_width = 20;
  int window_height = 20;
  grid::StateThresholds thresholds;
};

struct QualityScores {
  std::optional<double> map_score;                    // MS
  std::optional<double> cross_correlation;            // CC (Baron)
  std::optional<double> pearson_occupied;             // PC
  std::optional<double> occupied_picture_distance;    // OPDF
  std::optional<double> unoccupied_picture_distance;  // UPDF
};

// All five. Errors (kInvalidArgument): different size, resolution or origin; window < 1.
StatusOr<QualityScores> CompareMaps(const grid::OccupancyGrid& robot,
                                    const grid::OccupancyGrid& truth,
                                    const QualityOptions& options = {});

// Each on its own (same errors as CompareMaps).
StatusOr<std::optional<double>> MapScore(const grid::OccupancyGrid& robot,
                                         const grid::OccupancyGrid& truth,
                                         const QualityOptions& options = {});
StatusOr<std::optional<double>> CrossCorrelation(const grid::OccupancyGrid& robot,
                                                 const grid::OccupancyGrid& truth,
                                                 const QualityOptions& options = {});
StatusOr<std::optional<double>> PearsonOccupied(const grid::OccupancyGrid& robot,
                                                const grid::OccupancyGrid& truth,
                                                const QualityOptions& options = {});
StatusOr<std::optional<double>> OccupiedPictureDistance(const grid::OccupancyGrid& robot,
                                                        const grid::OccupancyGrid& truth,
                                                        const QualityOptions& options = {});
StatusOr<std::optional<double>> UnoccupiedPictureDistance(const grid::OccupancyGrid& robot,
                                                          const grid::OccupancyGrid& truth,
                                                          const QualityOptions& options = {});

}  // namespace fleetmap::metrics
