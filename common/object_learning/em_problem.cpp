#include "common/object_learning/em_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "common/object_learning/alignment_search.hpp"
#include "common/object_learning/e_step.hpp"
#include "common/object_learning/patch_transform.hpp"

namespace fleetmap::object_learning {

int EmProblem::max_per_map() const {
  size_t most = 0;
  for (const std::vector<int>& m : maps) most = std::max(most, m.size());
  return static_cast<int>(most);
}

Eigen::MatrixXd AlignedMatrix(const EmProblem& problem, const std::vector<Alignment>& alignments) {
  const int cells = problem.cells();
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(
      problem.snapshots.size(), cells);
  for (size_t s = 0; s < problem.snapshots.size(); ++s) {
    TransformPatchInto(problem.snapshots[s], alignments[s], rows.row(s).data());
  }
  return rows.cast<double>();
}

Eigen::MatrixXd SnapshotLogLikelihoods(const Eigen::MatrixXd& aligned,
                                       const Eigen::MatrixXd& objects, double sigma) {
  // |f - theta|^2 = |f|^2 - 2 f.theta + |theta|^2, all pairs at once.
  Eigen::MatrixXd d = -2.0 * aligned * objects.transpose();
  d.colwise() += aligned.rowwise().squaredNorm();
  d.rowwise() += objects.rowwise().squaredNorm().transpose();
  return -d.cwiseMax(0.0) / (2.0 * sigma * sigma);
}

CorrespondenceStep CorrespondenceEStep(const EmProblem& problem,
                                       const Eigen::MatrixXd& log_likelihoods,
                                       const EmOptions& options, std::mt19937_64* random) {
  const Eigen::Index n = log_likelihoods.cols();
  CorrespondenceStep step;
  step.expectations = Eigen::MatrixXd::Zero(log_likelihoods.rows(), n);
  for (const std::vector<int>& map : problem.maps) {
    if (map.empty()) continue;
    Eigen::MatrixXd local(map.size(), n);
    for (size_t k = 0; k < map.size(); ++k) local.row(k) = log_likelihoods.row(map[k]);
    CorrespondenceExpectations e;
    if (static_cast<int>(map.size()) <= options.max_exact_snapshots) {
      e = ExactCorrespondences(local);
    } else {
      e = SampledCorrespondences(local, options.gibbs_sweeps, options.gibbs_burn_in, random);
      step.approximate = true;
    }
    for (size_t k = 0; k < map.size(); ++k) step.expectations.row(map[k]) = e.expectations.row(k);
    step.log_likelihood +=
        e.log_normalizer - LogInjectiveCount(static_cast<int>(n), static_cast<int>(map.size()));
  }
  return step;
}

std::vector<int> MapAssignments(const EmProblem& problem, const Eigen::MatrixXd& log_likelihoods,
                                const EmOptions& options) {
  std::vector<int> result(log_likelihoods.rows(), -1);
  for (const std::vector<int>& map : problem.maps) {
    if (map.empty()) continue;
    Eigen::MatrixXd local(map.size(), log_likelihoods.cols());
    for (size_t k = 0; k < map.size(); ++k) local.row(k) = log_likelihoods.row(map[k]);
    const std::vector<int> a = static_cast<int>(map.size()) <= options.max_exact_snapshots
                                   ? BestAssignment(local)
                                   : GreedyAssignment(local);
    for (size_t k = 0; k < map.size(); ++k) result[map[k]] = a[k];
  }
  return result;
}

void AlignmentStep(const EmProblem& problem, const Eigen::MatrixXd& correspondences,
                   const Eigen::MatrixXd& objects, bool scan_rotations, const EmOptions& options,
                   std::vector<Alignment>* alignments) {
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      (correspondences * objects).cast<float>();
  for (size_t s = 0; s < problem.snapshots.size(); ++s) {
    (*alignments)[s] = AlignSnapshot(problem.snapshots[s], targets.row(s).data(), (*alignments)[s],
                                     scan_rotations, 0.25, options)
                           .alignment;
  }
}

void RandomStart(const EmProblem& problem, int num_objects, const EmOptions& options,
                 std::mt19937_64* random, Eigen::MatrixXd* objects,
                 std::vector<Alignment>* alignments) {
  const int count = static_cast<int>(problem.snapshots.size());
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  // Partial Fisher-Yates with our own uniform draw (reproducible across standard libraries).
  for (int i = 0; i < std::min(num_objects, count); ++i) {
    const int j = i + static_cast<int>(UniformDouble(random) * (count - i));
    std::swap(order[i], order[std::min(j, count - 1)]);
  }
  const int cells = problem.cells();
  *objects = Eigen::MatrixXd::Zero(num_objects, cells);
  for (int n = 0; n < num_objects; ++n) {
    const Patch& seed = problem.snapshots[order[n % count]];
    for (int i = 0; i < cells; ++i) (*objects)(n, i) = seed.occupancy[i];
  }
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      objects->cast<float>();
  EmOptions scan = options;
  scan.min_shift_step = options.initial_shift_step;  // the scan only: one coarse climb round
  alignments->assign(count, Alignment{});
  for (int s = 0; s < count; ++s) {
    double best = std::numeric_limits<double>::infinity();
    for (int n = 0; n < num_objects; ++n) {
      const AlignmentResult r =
          AlignSnapshot(problem.snapshots[s], targets.row(n).data(), Alignment{}, true, 1.0, scan);
      if (r.squared_distance < best) {
        best = r.squared_distance;
        (*alignments)[s] = r.alignment;
      }
    }
  }
}

double GaussianLogConstant(double count, double s) {
  return -count * std::log(std::sqrt(2.0 * std::numbers::pi) * s);
}

double Annealed(double final_value, double initial_value, double kappa, int j) {
  return std::max(final_value, initial_value * std::pow(kappa, j));
}

}  // namespace fleetmap::object_learning

namespace fleetmap::object_learning {

EmProblem MakeEmProblem(const SnapshotSet& set) {
  EmProblem problem;
  problem.maps.resize(set.per_map.size());
  for (size_t s = 0; s < set.snapshots.size(); ++s) {
    problem.snapshots.push_back(set.snapshots[s].patch);
    problem.maps[set.snapshots[s].map_index].push_back(static_cast<int>(s));
  }
  return problem;
}

}  // namespace fleetmap::object_learning
