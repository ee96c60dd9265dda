#include "common/object_learning/flat_em.hpp"

#include <random>

#include "common/core/check.hpp"
#include "common/object_learning/m_step.hpp"

namespace fleetmap::object_learning {
namespace {

constexpr double kExpectationTolerance = 1e-3;
constexpr double kModelTolerance = 1e-2;  // occupancy: a percent

}  // namespace

EmResult RunFlatEm(const EmProblem& problem, int num_objects, const EmOptions& options,
                   uint64_t seed, const std::function<void(int)>& on_iteration) {
  FLEETMAP_CHECK(num_objects >= problem.max_per_map());
  std::mt19937_64 random(seed);
  EmResult r;
  RandomStart(problem, num_objects, options, &random, &r.objects, &r.alignments);
  r.templates.resize(0, problem.cells());
  r.responsibilities.resize(num_objects, 0);
  Eigen::MatrixXd previous_c;
  for (int j = 0; j < options.iterations; ++j) {
    const double sigma = Annealed(options.sigma, options.sigma_initial, options.annealing, j);
    const CorrespondenceStep c = CorrespondenceEStep(
        problem, SnapshotLogLikelihoods(problem, r.alignments, r.objects, sigma), options, &random);
    r.approximate = r.approximate || c.approximate;
    r.correspondences = c.expectations;
    const Eigen::MatrixXd previous_objects = r.objects;
    r.objects = FlatMStep(WeightedSnapshotSums(problem, r.alignments, r.correspondences, r.objects),
                          r.correspondences, r.objects);
    AlignmentStep(problem, r.correspondences, r.objects, j % options.rotation_scan_every == 0,
                  options, &r.alignments);
    r.iterations = j + 1;
    if (on_iteration) on_iteration(r.iterations);
    if (sigma == options.sigma && previous_c.size() == r.correspondences.size() &&
        (r.correspondences - previous_c).cwiseAbs().maxCoeff() < kExpectationTolerance &&
        (r.objects - previous_objects).cwiseAbs().maxCoeff() < kModelTolerance) {
      break;
    }
    previous_c = r.correspondences;
  }
  const Eigen::MatrixXd ll =
      SnapshotLogLikelihoods(problem, r.alignments, r.objects, options.sigma);
  const CorrespondenceStep c = CorrespondenceEStep(problem, ll, options, &random);
  r.approximate = r.approximate || c.approximate;
  r.correspondences = c.expectations;
  r.snapshot_object = MapAssignments(problem, ll, options);
  r.log_likelihood = c.log_likelihood + GaussianLogConstant(ObservedCells(problem), options.sigma);
  return r;
}

}  // namespace fleetmap::object_learning
