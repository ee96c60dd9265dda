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

namespace {

// The content size of every row of `rows` (patches of the problem's size).
std::vector<ShapeSize> RowSizes(
    const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& rows,
    const EmProblem& problem) {
  const scene::Patch& shape = problem.snapshots.front();
  std::vector<ShapeSize> sizes;
  for (Eigen::Index n = 0; n < rows.rows(); ++n) {
    sizes.push_back(SizeOfContent(rows.row(n).data(), shape.width, shape.height));
  }
  return sizes;
}

}  // namespace

EmProblem MakeEmProblem(const SnapshotSet& set) {
  EmProblem problem;
  problem.maps.resize(set.per_map.size());
  for (size_t s = 0; s < set.snapshots.size(); ++s) {
    problem.snapshots.push_back(set.snapshots[s].patch);
    problem.maps[set.snapshots[s].map_index].push_back(static_cast<int>(s));
  }
  return problem;
}

int EmProblem::max_per_map() const {
  size_t most = 0;
  for (const std::vector<int>& m : maps) most = std::max(most, m.size());
  return static_cast<int>(most);
}

Eigen::MatrixXd SnapshotLogLikelihoods(const EmProblem& problem, const PairAlignments& alignments,
                                       const Eigen::MatrixXd& objects, double sigma) {
  const int cells = problem.cells();
  const Eigen::Index count = static_cast<Eigen::Index>(problem.snapshots.size());
  Eigen::MatrixXd ll(count, objects.rows());
  std::vector<float> values(cells), weights(cells);
  const Eigen::MatrixXd by_cell = objects.transpose();  // each object's cells contiguous
  for (Eigen::Index s = 0; s < count; ++s) {
    const PatchSampler sampler(problem.snapshots[s]);
    for (Eigen::Index n = 0; n < objects.rows(); ++n) {
      sampler.Sample(alignments[s][n], values.data(), weights.data());
      double sum = 0.0;
      for (int i = 0; i < cells; ++i) {
        const double d = values[i] - by_cell(i, n);
        sum += weights[i] * d * d;
      }
      ll(s, n) = -sum / (2.0 * sigma * sigma);
    }
  }
  return ll;
}

constexpr double kNegligibleCorrespondence = 1e-9;

Eigen::MatrixXd WeightedSnapshotSums(const EmProblem& problem, const PairAlignments& alignments,
                                     const Eigen::MatrixXd& correspondences,
                                     const Eigen::MatrixXd& objects) {
  const int cells = problem.cells();
  const Eigen::Index n_count = correspondences.cols();
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(objects.cols(), n_count);  // cells x N
  std::vector<float> values(cells), weights(cells);
  const Eigen::MatrixXd by_cell = objects.transpose();
  for (size_t s = 0; s < problem.snapshots.size(); ++s) {
    const PatchSampler sampler(problem.snapshots[s]);
    for (Eigen::Index n = 0; n < n_count; ++n) {
      // A pair this unlikely adds less than 1e-9 of a snapshot to any cell: not worth resampling.
      const double c = correspondences(static_cast<Eigen::Index>(s), n);
      if (c < kNegligibleCorrespondence) continue;
      sampler.Sample(alignments[s][n], values.data(), weights.data());
      for (int i = 0; i < cells; ++i) {
        sums(i, n) += c * (weights[i] * values[i] + (1.0 - weights[i]) * by_cell(i, n));
      }
    }
  }
  return sums.transpose();
}

double ObservedCells(const EmProblem& problem) {
  double total = 0.0;
  for (const scene::Patch& p : problem.snapshots) {
    if (p.weight.empty()) {
      total += static_cast<double>(p.occupancy.size());
    } else {
      for (float w : p.weight) total += w;
    }
  }
  return total;
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
                   const Eigen::MatrixXd& objects, bool all_pairs, const EmOptions& options,
                   PairAlignments* alignments) {
  // Below this weight a pair does not move the M-step; it is re-aligned on all_pairs steps.
  constexpr double kActive = 1e-3;
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      objects.cast<float>();
  const std::vector<ShapeSize> object_sizes = RowSizes(targets, problem);
  for (size_t s = 0; s < problem.snapshots.size(); ++s) {
    const scene::Patch& snapshot = problem.snapshots[s];
    const ShapeSize size =
        SizeOfContent(snapshot.occupancy.data(), snapshot.width, snapshot.height);
    for (Eigen::Index n = 0; n < objects.rows(); ++n) {
      if (!all_pairs && correspondences(s, n) < kActive) continue;
      // An unlike pair that carries no weight is not worth a rotation scan.
      if (all_pairs && correspondences(s, n) < kActive && !MayMatch(size, object_sizes[n])) {
        continue;
      }
      (*alignments)[s][n] = AlignSnapshot(problem.snapshots[s], targets.row(n).data(),
                                          (*alignments)[s][n], all_pairs, 0.25, options)
                                .alignment;
    }
  }
}

void RandomStart(const EmProblem& problem, int num_objects, const EmOptions& options,
                 std::mt19937_64* random, Eigen::MatrixXd* objects, PairAlignments* alignments) {
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
    const scene::Patch& seed = problem.snapshots[order[n % count]];
    for (int i = 0; i < cells; ++i) (*objects)(n, i) = seed.occupancy[i];
  }
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      objects->cast<float>();
  EmOptions scan = options;
  scan.min_shift_step = options.initial_shift_step;  // the scan and one coarse climb round
  alignments->assign(count, std::vector<Alignment>(num_objects));
  const std::vector<ShapeSize> object_sizes = RowSizes(targets, problem);
  for (int s = 0; s < count; ++s) {
    const scene::Patch& snapshot = problem.snapshots[s];
    const ShapeSize size =
        SizeOfContent(snapshot.occupancy.data(), snapshot.width, snapshot.height);
    for (int n = 0; n < num_objects; ++n) {
      (*alignments)[s][n] =
          MayMatch(size, object_sizes[n])
              ? AlignSnapshot(snapshot, targets.row(n).data(), Alignment{}, true, 1.0, scan)
                    .alignment
              : CentroidAlignment(snapshot, targets.row(n).data()).alignment;
    }
  }
}

std::vector<Alignment> AssignedAlignments(const PairAlignments& alignments,
                                          const std::vector<int>& snapshot_object) {
  std::vector<Alignment> out;
  for (size_t s = 0; s < alignments.size(); ++s) {
    out.push_back(snapshot_object[s] >= 0 ? alignments[s][snapshot_object[s]] : Alignment{});
  }
  return out;
}

double GaussianLogConstant(double count, double s) {
  return -count * std::log(std::sqrt(2.0 * std::numbers::pi) * s);
}

double Annealed(double final_value, double initial_value, double kappa, int j) {
  return std::max(final_value, initial_value * std::pow(kappa, j));
}

}  // namespace fleetmap::object_learning
