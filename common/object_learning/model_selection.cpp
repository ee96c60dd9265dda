#include "common/object_learning/model_selection.hpp"

#include <algorithm>
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
                        const LearnOptions& options) {
  EmResult best;
  best.log_likelihood = -std::numeric_limits<double>::infinity();
  for (int r = 0; r < options.restarts; ++r) {
    const uint64_t seed = RestartSeed(options.seed, num_objects, num_templates, r);
    EmResult run = options.hierarchical
                       ? RunHierarchicalEm(problem, num_objects, num_templates, options.em, seed)
                       : RunFlatEm(problem, num_objects, options.em, seed);
    if (r == 0 || run.log_likelihood > best.log_likelihood) best = std::move(run);
  }
  return best;
}

double LogPosterior(const EmResult& result, int num_objects, int num_templates,
                    const SelectionOptions& options) {
  return result.log_likelihood - options.object_penalty * num_objects -
         options.template_penalty * num_templates;
}

SelectionResult SelectModel(const EmProblem& problem, const LearnOptions& options) {
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
    int m_since_best = 0;
    for (int m = m_lo; m <= m_hi; ++m) {
      if (options.cancel != nullptr && options.cancel->load()) {
        result.cancelled = true;
        return result;
      }
      EmResult run = BestOfRestarts(problem, n, m, options);
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
    if (improved_n) {
      n_since_best = 0;
    } else if (patience > 0 && ++n_since_best >= patience) {
      break;
    }
  }
  if (capped && last_n == highest && result.num_objects >= highest - patience) {
    result.warnings.push_back("the number of objects was searched up to " +
                              std::to_string(highest) + " (selection.max_objects), not " +
                              std::to_string(total) + " (all snapshots), and the best was near it");
  }
  return result;
}

}  // namespace fleetmap::object_learning
