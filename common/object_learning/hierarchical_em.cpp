#include "common/object_learning/hierarchical_em.hpp"

#include <cassert>
#include <cmath>
#include <random>

#include "common/object_learning/e_step.hpp"
#include "common/object_learning/m_step.hpp"

namespace fleetmap::object_learning {
namespace {

// -|theta_n - alpha_m|^2 / (2 tau^2), N x M.
Eigen::MatrixXd TemplateLogWeights(const Eigen::MatrixXd& objects, const Eigen::MatrixXd& templates,
                                   double tau) {
  Eigen::MatrixXd d = -2.0 * objects * templates.transpose();
  d.colwise() += objects.rowwise().squaredNorm();
  d.rowwise() += templates.rowwise().squaredNorm().transpose();
  return -d.cwiseMax(0.0) / (2.0 * tau * tau);
}

// Converged: annealing is over and nothing moves any more.
constexpr double kExpectationTolerance = 1e-3;
constexpr double kModelTolerance = 1e-4;

}  // namespace

double ObjectLevelLogLikelihood(const Eigen::MatrixXd& objects, const Eigen::MatrixXd& templates,
                                double tau) {
  const Eigen::MatrixXd w = TemplateLogWeights(objects, templates, tau);
  double sum = 0.0;
  for (Eigen::Index n = 0; n < w.rows(); ++n) {
    sum += LogSumExp(w.row(n).transpose()) - std::log(static_cast<double>(templates.rows()));
  }
  return sum + GaussianLogConstant(static_cast<double>(objects.rows()) * objects.cols(), tau);
}

EmResult RunHierarchicalEm(const EmProblem& problem, int num_objects, int num_templates,
                           const EmOptions& options, uint64_t seed) {
  assert(num_templates >= 1 && num_templates <= num_objects);
  assert(num_objects >= problem.max_per_map());
  std::mt19937_64 random(seed);
  EmResult r;
  RandomStart(problem, num_objects, options, &random, &r.objects, &r.alignments);
  // Templates start as M distinct objects.
  std::vector<int> order(num_objects);
  for (int i = 0; i < num_objects; ++i) order[i] = i;
  for (int i = 0; i < num_templates; ++i) {
    const int j = i + static_cast<int>(UniformDouble(&random) * (num_objects - i));
    std::swap(order[i], order[std::min(j, num_objects - 1)]);
  }
  r.templates.resize(num_templates, problem.cells());
  for (int m = 0; m < num_templates; ++m) r.templates.row(m) = r.objects.row(order[m]);

  Eigen::MatrixXd previous_c, previous_z;
  for (int j = 0; j < options.iterations; ++j) {
    const double sigma = Annealed(options.sigma, options.sigma_initial, options.annealing, j);
    const double tau = Annealed(options.tau, options.tau_initial, options.annealing, j);
    const Eigen::MatrixXd aligned = AlignedMatrix(problem, r.alignments);
    const CorrespondenceStep c = CorrespondenceEStep(
        problem, SnapshotLogLikelihoods(aligned, r.objects, sigma), options, &random);
    r.approximate = r.approximate || c.approximate;
    r.correspondences = c.expectations;
    r.responsibilities = Responsibilities(TemplateLogWeights(r.objects, r.templates, tau));
    const Eigen::MatrixXd previous_objects = r.objects;
    HierarchicalParameters p =
        HierarchicalMStep(aligned, r.correspondences, r.responsibilities, sigma, tau, r.templates);
    r.objects = std::move(p.objects);
    r.templates = std::move(p.templates);
    AlignmentStep(problem, r.correspondences, r.objects, j % options.rotation_scan_every == 0,
                  options, &r.alignments);
    r.iterations = j + 1;
    const bool annealed = sigma == options.sigma && tau == options.tau;
    if (annealed && previous_c.size() == r.correspondences.size() &&
        (r.correspondences - previous_c).cwiseAbs().maxCoeff() < kExpectationTolerance &&
        (r.responsibilities - previous_z).cwiseAbs().maxCoeff() < kExpectationTolerance &&
        (r.objects - previous_objects).cwiseAbs().maxCoeff() < kModelTolerance) {
      break;
    }
    previous_c = r.correspondences;
    previous_z = r.responsibilities;
  }

  // The final E-step and the log joint at the final noise levels.
  const Eigen::MatrixXd aligned = AlignedMatrix(problem, r.alignments);
  const Eigen::MatrixXd ll = SnapshotLogLikelihoods(aligned, r.objects, options.sigma);
  const CorrespondenceStep c = CorrespondenceEStep(problem, ll, options, &random);
  r.approximate = r.approximate || c.approximate;
  r.correspondences = c.expectations;
  r.responsibilities = Responsibilities(TemplateLogWeights(r.objects, r.templates, options.tau));
  r.snapshot_object = MapAssignments(problem, ll, options);
  r.object_template.resize(num_objects);
  for (int n = 0; n < num_objects; ++n) {
    Eigen::Index best = 0;
    r.responsibilities.row(n).maxCoeff(&best);
    r.object_template[n] = static_cast<int>(best);
  }
  r.log_likelihood =
      c.log_likelihood +
      GaussianLogConstant(static_cast<double>(problem.snapshots.size()) * problem.cells(),
                          options.sigma) +
      ObjectLevelLogLikelihood(r.objects, r.templates, options.tau);
  return r;
}

}  // namespace fleetmap::object_learning
