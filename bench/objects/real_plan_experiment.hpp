#pragma once

// The object learner on a real-plan series (RealPlanSeries): learns from its maps as
// `fleetmap learn-objects` would and scores what it found against the pieces drawn. A snapshot
// finds a piece when its centre lies within `match_distance` of the piece's centre in the same
// map (one-to-one, nearest pairs first). Precision: snapshots that found a piece over all
// snapshots; recall: pieces found over pieces drawn. Also the learned (N, M), the time and the
// process's peak resident memory while learning.
//
// Thread-safety: stateless, but the peak memory is the whole process's: run one at a time.

#include <cstdint>
#include <string>
#include <vector>

#include "bench/objects/real_plan_series.hpp"
#include "common/object_learning/learn_options.hpp"
#include "common/object_learning/object_learner.hpp"

namespace fleetmap::bench {

struct RealPlanScore {
  int snapshots = 0;
  int true_pieces = 0;  // pieces drawn, summed over the maps
  int matched = 0;      // one-to-one snapshot-piece pairs within the distance
  double precision = 0.0;
  double recall = 0.0;
  std::vector<PlacedPiece> missed;  // pieces no snapshot found (their map in `piece`'s order)
  std::vector<int> missed_map;
  std::vector<object_learning::SnapshotAssignment> spurious;  // snapshots that found no piece
};

// Scores the snapshots of `model` against the pieces of `series`.
RealPlanScore ScoreAgainstPieces(const RealPlanSeries& series,
                                 const object_learning::LearnedModel& model, double match_distance);

struct RealPlanResult {
  std::string floor;
  int maps = 0;
  int pieces = 0;  // per map (as asked)
  int shapes = 0;  // distinct shapes drawn
  int unplaced = 0;
  RealPlanScore score;
  int num_objects = 0;
  int num_templates = 0;
  int searched = 0;  // (N, M) candidates tried
  double seconds = 0.0;
  int64_t peak_rss_bytes = 0;  // -1 when it could not be read
  double estimated_mb = 0.0;   // the learner's own estimate of its peak (LearnedModel)
  bool peak_reset = false;     // the peak was reset before learning (else it includes earlier work)
  std::vector<std::string> warnings;
};

// Learns on the series with `learn`; fails when the learner does (the message says so).
StatusOr<RealPlanResult> RunRealPlanExperiment(const RealPlanSeries& series,
                                               const object_learning::LearnOptions& learn,
                                               double match_distance = 0.3);

}  // namespace fleetmap::bench
