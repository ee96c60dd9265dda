#pragma once

// Map-to-map registration: the rigid transform (x, y, yaw) that takes map B's frame into map A's
// frame, estimated from two occupancy grids, with a verification that refuses ambiguous or
// unsupported matches. See docs/registration.md for the method and what confidence means.
//
// Register() is a pure function of its inputs: any thread may call it, concurrently too.

#include <string>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::registration {

// The placement bar: the least confidence at which a registration is found. One bar for every
// user of Register: the server places a robot exactly when Registration::found is true (its
// --placement-confidence sets RegistrationOptions::min_confidence), `fleetmap register` says
// "found: yes" at the same bar by default, and the pair benchmark counts found pairs with it.
// Confidence is the calibrated probability that a placement is right and a wrong placement is
// worse than none (it spoils the fused map until it is revised), so the bar is high.
inline constexpr double kPlacementConfidence = 0.95;

struct RegistrationOptions {
  // The coarse search works on grids of at most this many cells squared (each coarse cell is
  // the max of f x f map cells, f an integer >= 1).
  int max_search_cells = 160;
  // Yaw step of the exhaustive coarse search (degrees) and of the final refinement.
  double coarse_yaw_step_deg = 1.5;
  double fine_yaw_step_deg = 0.05;
  // Width (in coarse cells) of the Gaussian likelihood field around A's occupied cells.
  double field_sigma_cells = 1.2;
  // What one of B's occupied cells costs on A's free space, far from A's walls (a field value of
  // 1 is a perfect hit).
  double free_penalty = 1.0;
  // Levels of the branch-and-bound max-pyramid (the top level spans 2^(levels-1) coarse cells).
  int pyramid_levels = 7;
  // Most of B's occupied cells the coarse search and the refinement score (evenly thinned).
  int max_search_points = 500;
  int max_refine_points = 4000;
  // Two hypotheses are "clearly different" when B's centroid lands farther apart than this (in
  // coarse cells) or their yaws differ by more than distinct_yaw_deg.
  double distinct_cells = 4.0;
  double distinct_yaw_deg = 5.0;
  // Clearly different coarse peaks refined and verified at full resolution; the best verified
  // one wins.
  int candidates = 10;
  // A candidate's verification value: agreeing occupied cells (both ways) less this weight times
  // contradicting ones.
  double verify_contradiction_weight = 2.0;
  // A match is refused when the best clearly different candidate verifies at least this fraction
  // of the best one's value (symmetric arenas, corridors, repeated rooms).
  double max_peak_ratio = 0.85;
  // ... and when a candidate turned by more than symmetry_min_yaw_deg against the best has at
  // least symmetry_min_agreement of its agreeing cells with a consistency (agreeing / (agreeing
  // + contradicting)) at most symmetry_max_consistency_drop below the best's: the structure
  // repeats under a rotation (a point-symmetric arena), whatever the values say.
  double symmetry_min_yaw_deg = 10.0;
  double symmetry_min_agreement = 0.5;
  double symmetry_max_consistency_drop = 0.1;
  // A rival of the best (a turned twin as above, or any candidate verifying above 70 % of the
  // best's value) is told apart, and left out of both tests and of the score, where the two
  // disagree (PlacementVerifier::Discriminate): at least symmetry_telling_m of walls (occupied
  // cells of either map, times the resolution) that the best lays on the other map's walls and
  // the rival on its free space, and at most symmetry_telling_ratio of that the other way
  // round. A warehouse turned half a turn is its racks again, but not its pallets and pillars.
  // 0 m: no rival is ever told apart.
  double symmetry_telling_m = 2.0;
  double symmetry_telling_ratio = 0.25;
  // Drift (docs/registration.md, *Drift*): the finalists are verified with each block of B,
  // drift_block_m square, shifted on A by up to max_drift_per_m of the block's distance from the
  // centre of the rigid agreement, and never more than max_drift_cells. The placement stays one
  // rigid transform; 0 for either bound verifies rigidly (ConfidenceCalibration::Default()).
  // 0.03 (3 cm per metre: a 2 % scale error and a heading that creeps) is the value the
  // drift-tolerant calibration was fitted at; on by default since 2026-12-07 (docs/results.md).
  double drift_block_m = 3.0;
  double max_drift_per_m = 0.03;
  int max_drift_cells = 8;
  // Verification at full resolution: occupied cells agree when the other map has an occupied cell
  // within tolerance_cells; they contradict when they land on a free cell with none within it.
  int tolerance_cells = 1;
  // Least number of B's occupied cells that must agree with A (the shared structure): at least
  // min_agreeing_cells, and at least min_agreeing_share of B's occupied cells that land on A's
  // known cells (what B could show in the overlap), so the bar scales with the evidence.
  int min_agreeing_cells = 40;
  double min_agreeing_share = 0.5;
  // Least share of B's known cells that must land on A's known cells: the relative bar above
  // lets a sliver of overlap agree perfectly, so a placement must also share this much.
  double min_overlap = 0.1;
  // Most contradicting occupied cells (both directions) as a fraction of agreeing + contradicting.
  double max_contradiction = 0.25;
  // Least score (consistency x distinctness, Registration::score) a match must have to be found.
  double min_score = 0.15;
  // Least confidence (Registration::confidence) a match that passed every check above must have
  // to be found: the placement bar.
  double min_confidence = kPlacementConfidence;
  // How a cell value reads as occupied / free.
  grid::StateThresholds thresholds;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

struct Registration {
  // The decision: the placement passed the verification (shared structure, contradiction,
  // ambiguity, score) and its confidence reaches RegistrationOptions::min_confidence. The server
  // places a robot exactly when this is true.
  bool found = false;
  // The placement passed every check of the verification; only its confidence may be below the
  // bar. The placer's sequential test counts such placements when they keep winning.
  bool verified = false;
  // Takes a point in B's map frame to A's map frame: p_a = a_from_b * p_b. The best hypothesis,
  // also when it is refused (then a hint only).
  Pose2 a_from_b;
  // The estimated probability that a_from_b is right (within 3 cells at B's known centroid and
  // 2 degrees): `score` through ConfidenceCalibration::DriftTolerant() (Default() when the
  // verification is rigid), fitted on synthetic pairs.
  double confidence = 0.0;
  // The evidence in [0, 1]: consistency (agreeing / (agreeing + contradicting) occupied cells,
  // both ways) times distinctness (1 - second candidate's verification / best's, scaled). 0 when
  // nothing matched.
  double score = 0.0;
  // Fraction of B's known cells that land on A's known cells under a_from_b.
  double overlap = 0.0;
  // Why found is false, for people (the verification's reason, or "confidence 0.72 below the
  // placement bar 0.95"); empty when found.
  std::string why_not;
  // The figures behind the decision.
  // The largest shift (metres) a block of B took in the drift-tolerant verification: how far
  // B's walls are from A's where they are farthest, under a_from_b (0 for a rigid fit).
  double drift = 0.0;
  int agreeing_cells = 0;
  int contradicting_cells = 0;
  // How well the best clearly different placement verifies, as a fraction of the best's (1 when
  // a turned placement explains B's walls about as well: a symmetry).
  double peak_ratio = 0.0;
  // The finalists (refined and verified at full resolution, clearly different), best first:
  // the first is a_from_b. For diagnostics: the pair benchmark reads them to tell a right
  // placement that was never a finalist from one that was outranked.
  std::vector<Pose2> finalists;
};

// Estimates a_from_b. Errors (kInvalidArgument): options invalid, an empty map, a map without
// occupied cells, a non-finite origin or resolution, or resolutions that differ (refused, not
// resampled: resample one map first, e.g. with the tool that made it).
StatusOr<Registration> Register(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                                const RegistrationOptions& options);

}  // namespace fleetmap::registration
