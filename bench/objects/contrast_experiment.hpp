#pragma once

// The object-learning paper's central contrast, searched for (issue 36): under which condition does
// flat EM (objects only) fall into poor local maxima where hierarchical EM (objects and templates)
// does not? The paper: 20 of 20 good starts against 9 of 20 on its second data set. Each
// condition changes one thing against the paper's set-up (ALGORITHMS.md 2): more objects of fewer
// shapes, objects seen once or twice, no annealing, coarse rotation scans (poor initial
// alignments), unsmoothed snapshots. Each runs on several simulated data sets (data seeds), the
// same random starts for both models at the true (N, M). Used by `fleetmap bench objects
// --contrast`.

#include <cstdint>
#include <string>
#include <vector>

#include "bench/objects/object_experiment.hpp"
#include "common/core/status.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::bench {

struct ContrastCondition {
  std::string name;     // short, for tables: "paper", "many-of-few", ...
  std::string changed;  // what differs from the paper's set-up, for the report
  ObjectDatasetOptions data;
  object_learning::LearnOptions learn;
};

// The conditions, the paper's set-up first.
std::vector<ContrastCondition> ContrastConditions();

struct ContrastRunOptions {
  uint32_t first_seed = 1;  // data seeds first_seed .. first_seed + data_sets - 1
  int data_sets = 3;
  int starts = 20;  // random starts per model and data set
  // A start reached an optimum as good as the best when its training log-likelihood is within
  // this many nats of the best start's (of its model, on its data set): a likelihood ratio of at
  // most e^5, about 150. Good starts on the paper's set-up spread over 2-4 nats.
  double near_best_nats = 5.0;
  bool cross_validate = true;  // leave-one-map-out test log-likelihood (one EM run per map)
};

// One model's figures on one condition, summed over its data sets.
struct ContrastModel {
  int good = 0;                      // starts that reached the true partition (IsGoodSolution)
  int near_best = 0;                 // starts within near_best_nats of the best start
  double test_log_likelihood = 0.0;  // leave one map out, at the true (N, M)
  double seconds = 0.0;              // the starts
  std::vector<double> train_log_likelihood;  // per start, data set after data set
};

struct ContrastRow {
  std::string condition;
  std::string changed;
  int data_sets = 0;
  int maps = 0;  // summed over the data sets
  int snapshots = 0;
  int true_objects = 0;  // of one data set
  int true_templates = 0;
  int starts = 0;  // per model, summed over the data sets
  ContrastModel hierarchical;
  ContrastModel flat;
};

// Runs `condition` on the data seeds of `options`, both models from the same random starts.
// Errors: the simulation's (kInvalidArgument for options no lab can hold).
StatusOr<ContrastRow> RunContrastCondition(const ContrastCondition& condition,
                                           const ContrastRunOptions& options);

}  // namespace fleetmap::bench
