#include "common/object_learning/held_out_likelihood.hpp"

#include "common/core/check.hpp"
#include "common/object_learning/alignment_search.hpp"
#include "common/object_learning/e_step.hpp"
#include "common/object_learning/em_problem.hpp"

namespace fleetmap::object_learning {

double HeldOutLogLikelihood(const std::vector<scene::Patch>& snapshots,
                            const Eigen::MatrixXd& objects, const EmOptions& options) {
  const int k_count = static_cast<int>(snapshots.size());
  const int n_count = static_cast<int>(objects.rows());
  FLEETMAP_CHECK(n_count >= k_count);
  if (k_count == 0) return 0.0;
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      objects.cast<float>();
  Eigen::MatrixXd log_likelihood(k_count, n_count);
  for (int k = 0; k < k_count; ++k) {
    for (int n = 0; n < n_count; ++n) {
      const AlignmentResult r =
          AlignSnapshot(snapshots[k], targets.row(n).data(), Alignment{}, true, 1.0, options);
      log_likelihood(k, n) = -r.squared_distance / (2.0 * options.sigma * options.sigma);
    }
  }
  const double log_z = k_count <= options.max_exact_snapshots
                           ? ExactCorrespondences(log_likelihood).log_normalizer
                           : [&] {
                               const std::vector<int> a = GreedyAssignment(log_likelihood);
                               double w = 0.0;
                               for (int k = 0; k < k_count; ++k) w += log_likelihood(k, a[k]);
                               return w;
                             }();
  EmProblem held_out;
  held_out.snapshots = snapshots;
  return log_z - LogInjectiveCount(n_count, k_count) +
         GaussianLogConstant(ObservedCells(held_out), options.sigma);
}

}  // namespace fleetmap::object_learning
