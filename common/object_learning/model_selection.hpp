#pragma once

// Model selection over the number of objects N and templates M (ALGORITHMS.md 2, eqs. 29, 30):
// EM (with restarts, the best log joint kept) for every candidate max_t K_t <= N <= sum_t K_t,
// 1 <= M <= N, scored by log p(data, model) - c_N N - c_M M. Candidates are visited in order of
// N, and of M within N; with `patience` > 0 the search along M (and along N) stops after that many
// candidates in a row without a new best, since the score rises to its peak and then falls.
//
// Thread-safety: stateless.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/learn_options.hpp"
#include "common/object_learning/object_learner.hpp"

namespace fleetmap::object_learning {

struct SelectionResult {
  int num_objects = 0;
  int num_templates = 0;  // 0 for the flat model
  double log_posterior = 0.0;
  EmResult model;
  std::vector<ModelScore> searched;
  std::vector<std::string> warnings;
  bool cancelled = false;  // options.cancel was set: the result is incomplete
};

// The seed of one random start, derived from the user's seed and the candidate.
uint64_t RestartSeed(uint32_t seed, int num_objects, int num_templates, int restart);

// The best of options.restarts EM runs for a fixed (N, M) (hierarchical, or flat when
// options.hierarchical is false; M is ignored then).
// `on_iteration(restart, iteration)`, when set, is called after each EM iteration.
EmResult BestOfRestarts(const EmProblem& problem, int num_objects, int num_templates,
                        const LearnOptions& options,
                        const std::function<void(int, int)>& on_iteration = {});

// log p(data, model) - c_N N - c_M M.
double LogPosterior(const EmResult& result, int num_objects, int num_templates,
                    const SelectionOptions& options);

// Requires at least one snapshot.
// Reports progress through options.progress (stage kSearching), starting from `base` (maps,
// snapshots, and the elapsed seconds before the search); the search's own time is added.
SelectionResult SelectModel(const EmProblem& problem, const LearnOptions& options,
                            const LearnProgress& base = {});

}  // namespace fleetmap::object_learning
