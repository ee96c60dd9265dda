#include "common/object_learning/model_selection.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "common/core/check.hpp"
#include "common/object_learning/flat_em.hpp"
#include "common/object_learning/hierarchical_em.hpp"

namespace fleetmap::object_learning {

uint64_t RestartSeed(uint32_t seed, int num_objects, int num_templates, int restart) {
  // SplitMix64 of the packed inputs: well-spread, and the same on every platform.
  uint64_t z = (static_cast<uint64_t>(seed) << 32) ^ (static_cast<uint64_t>(num_objects) << 20) ^
               (static_cast<uint64_t>(num_templates) << 10) ^ static_cast<uint64_t>(restart);
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

EmResult BestOfRestarts(const EmProblem& problem, int num_objects, int num_templates,
                        const LearnOptions& options,
                        const std::function<void(int, int)>& on_iteration) {
  EmResult best;
  best.log_likelihood = -std::numeric_limits<double>::infinity();
  for (int r = 0; r < options.restarts; ++r) {
    const uint64_t seed = RestartSeed(options.seed, num_objects, num_templates, r);
    std::function<void(int)> iteration;
    if (on_iteration) iteration = [&on_iteration, r](int j) { on_iteration(r, j); };
    EmResult run =
        options.hierarchical
            ? RunHierarchicalEm(problem, num_objects, num_templates, options.em, seed, iteration)
            : RunFlatEm(problem, num_objects, options.em, seed, iteration);
    if (r == 0 || run.log_likelihood > best.log_likelihood) best = std::move(run);
  }
  return best;
}

double LogPosterior(const EmResult& result, int num_objects, int num_templates,
                    const SelectionOptions& options) {
  return result.log_likelihood - options.object_penalty * num_objects -
         options.template_penalty * num_templates;
}

SelectionResult SelectModel(const EmProblem& problem, const LearnOptions& options,
                            const LearnProgress& base) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  LearnProgress progress = base;
  progress.stage = LearnStage::kSearching;
  progress.snapshots = static_cast<int>(problem.snapshots.size());
  progress.restarts = options.restarts;
  progress.em_iterations = options.em.iterations;
  // Runs per N row so far, for the estimate of the runs left.
  int rows_done = 0, runs_in_done_rows = 0;
  const int total = static_cast<int>(problem.snapshots.size());
  FLEETMAP_CHECK(total > 0);
  const int lowest = std::max(1, problem.max_per_map());
  int highest = total;
  SelectionResult result;
  result.log_posterior = -std::numeric_limits<double>::infinity();
  const bool capped = highest > options.selection.max_objects;
  if (capped) highest = std::max(lowest, options.selection.max_objects);
  const int patience = options.selection.patience;
  int n_since_best = 0;
  int last_n = lowest;
  for (int n = lowest; n <= highest; ++n) {
    last_n = n;
    bool improved_n = false;
    const int m_lo = options.hierarchical ? 1 : 0;
    const int m_hi = options.hierarchical ? n : 0;
    double best_for_n = -std::numeric_limits<double>::infinity();
    const int runs_before_row = static_cast<int>(result.searched.size());
    int m_since_best = 0;
    for (int m = m_lo; m <= m_hi; ++m) {
      if (options.cancel != nullptr && options.cancel->load()) {
        result.cancelled = true;
        return result;
      }
      progress.num_objects = n;
      progress.num_templates = m;
      auto report = [&](int restart, int iteration) {
        if (!options.progress) return;
        progress.restart = restart;
        progress.em_iteration = iteration;
        const double seconds = elapsed();
        progress.elapsed_seconds = base.elapsed_seconds + seconds;
        // Runs left: this row until patience runs without a new best (or its end), then
        // `patience` more rows of the mean length so far (the search's usual end).
        const int left_in_row =
            patience > 0 ? std::min(m_hi - m, std::max(0, patience - m_since_best)) : m_hi - m;
        const double row_length = rows_done > 0 ? static_cast<double>(runs_in_done_rows) / rows_done
                                                : static_cast<double>(m - m_lo + 1 + left_in_row);
        const int left_rows = patience > 0
                                  ? std::max(0, std::min(highest - n, patience - n_since_best))
                                  : highest - n;
        const int left = left_in_row + static_cast<int>(std::lround(left_rows * row_length));
        progress.candidates_estimate = progress.candidates_done + 1 + left;
        const double done_fraction =
            progress.candidates_done +
            std::min(1.0, (restart + iteration / static_cast<double>(options.em.iterations)) /
                              options.restarts);
        progress.remaining_seconds =
            done_fraction > 0.25
                ? seconds / done_fraction * (progress.candidates_estimate - done_fraction)
                : -1.0;
        options.progress(progress);
      };
      report(0, 0);
      EmResult run = BestOfRestarts(problem, n, m, options, report);
      ++progress.candidates_done;
      const double score = LogPosterior(run, n, m, options.selection);
      result.searched.push_back({n, m, score});
      if (score > best_for_n) {
        best_for_n = score;
        m_since_best = 0;
      } else if (patience > 0 && ++m_since_best >= patience) {
        break;
      }
      if (score > result.log_posterior) {
        result.log_posterior = score;
        result.num_objects = n;
        result.num_templates = m;
        result.model = std::move(run);
        improved_n = true;
      }
    }
    ++rows_done;
    runs_in_done_rows += static_cast<int>(result.searched.size()) - runs_before_row;
    if (improved_n) {
      n_since_best = 0;
    } else if (patience > 0 && ++n_since_best >= patience) {
      break;
    }
  }
  if (capped && highest == lowest) {
    // A map shows more snapshots than max_objects: N cannot be smaller than that, and the cap
    // leaves only that one value to try.
    result.warnings.push_back("one map has " + std::to_string(lowest) +
                              " snapshots, more than selection.max_objects (" +
                              std::to_string(options.selection.max_objects) +
                              "): only N = " + std::to_string(lowest) + " was tried");
  } else if (capped && last_n == highest && result.num_objects >= highest - patience) {
    result.warnings.push_back("the number of objects was searched up to " +
                              std::to_string(highest) + " (selection.max_objects), not " +
                              std::to_string(total) + " (all snapshots), and the best was near it");
  }
  return result;
}

}  // namespace fleetmap::object_learning
