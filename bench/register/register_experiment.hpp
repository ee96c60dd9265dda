#pragma once

// The registration benchmark (issue 18, deliverable 5; issue 31): pairs of robot maps cut from
// complete maps at several overlaps (map_pair_generator.hpp), each registered by fleetmap's
// registration::Register and by the m-explore baseline (mexplore_registration.hpp) in the same
// run, judged against the truth; the same pairs again with B drifted (a smooth warp); terrains
// whose structure repeats (repeated_terrain.hpp) as a group of their own; plus the reliability
// of fleetmap's confidence. Used by `fleetmap bench register` and its tests.

#include <cstdint>
#include <string>
#include <vector>

#include "bench/register/map_pair_generator.hpp"
#include "common/core/progress_line.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/registration/registration.hpp"

namespace fleetmap::bench {

struct SourceMap {
  std::string name;
  grid::OccupancyGrid grid;
  std::string group = "maps";  // the summary's rows are per group (and overlap)
};

// `count` synthetic terrains (30 m, 5 cm cells), group "synthetic", seeds seed * 7919 + k: the
// kinds of common/sim (office, maze, unstructured) and the repeated ones (warehouse, office
// rows, corridors) in turn. The calibration set: source maps that are not the evaluation maps.
StatusOr<std::vector<SourceMap>> SyntheticSourceMaps(int count, uint32_t seed);

// `count` repeated-structure terrains (warehouse, office rows, corridors in turn; 30 m, 5 cm
// cells), group "repeated", seeds 1000000 + seed * 7919 + k: never the calibration set's.
StatusOr<std::vector<SourceMap>> RepeatedSourceMaps(int count, uint32_t seed);

struct RegisterBenchOptions {
  std::vector<double> overlaps = {0.20, 0.35, 0.50, 0.70};
  int pairs_per_overlap = 10;  // per source map and overlap
  uint32_t seed = 1;
  MapPairOptions pairs;
  // Every pair is registered a second time with B warped (group "<group> drifted").
  bool drift = true;
  DriftOptions drift_options;
  // registration.min_confidence is the placement bar: "found" means placed by the server.
  registration::RegistrationOptions registration;
  bool run_mexplore = true;
  // Success: translation error at B's known centroid within this many cells, yaw within this.
  double max_translation_cells = 3.0;
  double max_yaw_deg = 2.0;
};

// Where a placement is judged: a point of the registered B (map frame), where the truth lays it
// on A, and how the truth's yaw reads there.
struct JudgePoint {
  Point2 b;
  Point2 a;
  double yaw = 0.0;
};

struct MethodOutcome;

// A plain pair is rigid, so it is judged at B's known centroid. A drifted B has no rigid truth:
// it is judged where it overlaps A, the overlap's centroid carried by the warp (and the warp's
// turn there), since a rigid placement can be right there and nowhere else far from it.
JudgePoint PlainJudgePoint(const MapPair& pair, const Point2& centroid_b);
JudgePoint DriftedJudgePoint(const MapPair& pair, const Point2& pivot, double scale,
                             double bend_per_metre);

// Errors of an estimate at the judge point, in cells and degrees, into `outcome` (right,
// success).
void Judge(const MapPair& pair, const JudgePoint& at, const Pose2& estimate,
           const RegisterBenchOptions& options, MethodOutcome* outcome);

struct MethodOutcome {
  bool found = false;
  bool success = false;  // found, and within the tolerances of the truth
  bool right = false;    // the estimate (or best guess) is within the tolerances, found or not
  double translation_error_cells = 0.0;
  double yaw_error_deg = 0.0;
  double seconds = 0.0;
  double confidence = 0.0;  // fleetmap: Registration::confidence; m-explore: match confidence
  double score = 0.0;       // fleetmap: Registration::score (the uncalibrated evidence)
  std::string why_not;      // fleetmap: why it was refused
  // fleetmap: the evidence behind the score, and the rank among Registration::finalists of the
  // first right one (-1: none was right), which tells the stage that failed.
  int agreeing_cells = 0;
  int contradicting_cells = 0;
  double peak_ratio = 0.0;
  int right_finalist = -1;
};

struct PairOutcome {
  std::string map;
  std::string group;  // the source map's, with " drifted" for the warped pairs
  double target_overlap = 0.0;
  double overlap = 0.0;  // achieved
  int a_cells = 0;       // grid sizes (width x height)
  int b_cells = 0;
  MethodOutcome fleetmap;
  MethodOutcome mexplore;
};

struct RegisterBenchRun {
  std::vector<PairOutcome> pairs;
  int not_generated = 0;  // pairs the generator could not make within its tolerance
};

// Runs the benchmark on every source map; `progress` (may be null) shows the pairs done and
// prints a line for each pair the generator could not make.
RegisterBenchRun RunRegisterBench(const std::vector<SourceMap>& maps,
                                  const RegisterBenchOptions& options, ProgressLine* progress);

struct MethodSummary {
  int pairs = 0;
  int found = 0;
  int successes = 0;
  int false_accepts = 0;  // found but not a success
  double median_seconds = 0.0;
  double worst_seconds = 0.0;
  double success_percent() const { return pairs > 0 ? 100.0 * successes / pairs : 0.0; }
  double false_accept_percent() const { return pairs > 0 ? 100.0 * false_accepts / pairs : 0.0; }
};

// Per group (in order of first appearance), one row per target overlap and one for the group's
// pairs (target_overlap < 0); with more than one group, a last row for every pair (group empty).
struct SummaryRow {
  std::string group;
  double target_overlap = -1.0;
  double mean_overlap = 0.0;
  MethodSummary fleetmap;
  MethodSummary mexplore;
};

std::vector<SummaryRow> Summarize(const std::vector<PairOutcome>& pairs);

// Reliability of fleetmap's confidence: among found pairs, per confidence bin, how many were right.
struct ReliabilityBin {
  double lo = 0.0, hi = 1.0;  // confidence in [lo, hi) (the last bin includes 1)
  int found = 0;
  int correct = 0;
  double mean_confidence = 0.0;
};

std::vector<ReliabilityBin> Reliability(const std::vector<PairOutcome>& pairs);

// Expected calibration error over the found pairs: sum over bins of (found in bin / found) *
// |fraction correct - mean confidence|.
double ExpectedCalibrationError(const std::vector<ReliabilityBin>& bins);

}  // namespace fleetmap::bench
