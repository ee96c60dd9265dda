#pragma once

// The placer's sequential test on growing maps (issue 31, item 3): robot B's map as it grows
// (MapPair::b_growing, then B), each step registered on A as the server registers an unplaced
// robot's map on the fleet map, and the votes fed to the server's own PlacementEvidence under
// two rules side by side: the bar alone (two registrations in a row at the placement bar, the
// server's default) and the sequential one (also three verified wins in a row at 0.8 or more on
// a grown map: PlacementOptions::sequential_wins, off by default). Reports for
// each rule whether and at which step the robot would be placed, and whether rightly. Used by
// `fleetmap bench register --growing N`.

#include <cstdint>
#include <string>
#include <vector>

#include "bench/register/register_experiment.hpp"
#include "common/core/progress_line.hpp"
#include "common/registration/placement_evidence.hpp"

namespace fleetmap::bench {

struct GrowingBenchOptions {
  RegisterBenchOptions pairs;  // overlaps (of the full-grown B), pairs per overlap, seed, drift
  int steps = 5;               // registrations per pair, B after 1/steps, 2/steps, ... of its drive
  registration::PlacementEvidence::Options bar_only;  // the server's default
  registration::PlacementEvidence::Options sequential{.sequential_wins = 3};
};

// One rule's outcome on one growing pair.
struct RuleOutcome {
  int placed_at = 0;   // the step (1-based) at which it places; 0: never
  bool right = false;  // the placement it made is within the tolerances
};

struct GrowingPairOutcome {
  std::string map;
  std::string group;  // as in PairOutcome (" drifted" for warped B)
  double target_overlap = 0.0;
  // Per step: the registration's confidence, and whether it passed the verification and was
  // right (for the table of what the rules saw).
  std::vector<double> confidence;
  std::vector<uint8_t> verified;
  std::vector<uint8_t> right;
  std::vector<double> error_cells;  // of the best guess, at the judge point
  std::vector<double> score;
  std::vector<double> overlap;     // Registration::overlap
  std::vector<double> peak_ratio;  // Registration::peak_ratio
  RuleOutcome bar_only;
  RuleOutcome sequential;
  std::vector<double> seconds;  // per registration
};

struct GrowingBenchRun {
  std::vector<GrowingPairOutcome> pairs;
  int not_generated = 0;
};

GrowingBenchRun RunGrowingBench(const std::vector<SourceMap>& maps,
                                const GrowingBenchOptions& options, ProgressLine* progress);

struct RuleSummary {
  int placed = 0;
  int wrong = 0;           // placed, but not rightly
  double mean_step = 0.0;  // of the placements
};

struct GrowingSummaryRow {
  std::string group;  // empty: every pair
  int pairs = 0;
  RuleSummary bar_only;
  RuleSummary sequential;
};

// One row per group (in order of first appearance), and one for every pair when there are more.
std::vector<GrowingSummaryRow> SummarizeGrowing(const std::vector<GrowingPairOutcome>& pairs);

}  // namespace fleetmap::bench
