#pragma once

// What hierarchical and flat EM share: the snapshots grouped by map, the aligned-snapshot matrix,
// the snapshot-object log-likelihoods (eq. 1), the correspondence E-step over all maps (exact or
// sampled, eq. 19), the alignment M-step over all snapshots (eq. 26), and the random start.
//
// Thread-safety: an EmProblem is immutable once built; the functions are stateless.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "common/object_learning/learn_options.hpp"
#include "common/object_learning/patch.hpp"

namespace fleetmap::object_learning {

struct EmProblem {
  std::vector<Patch> snapshots;        // all of one size
  std::vector<std::vector<int>> maps;  // snapshot indices of each map (K_t = maps[t].size())
  int cells() const { return snapshots.empty() ? 0 : snapshots[0].width * snapshots[0].height; }
  int max_per_map() const;
};

// The model and correspondences one EM run ends with.
struct EmResult {
  Eigen::MatrixXd objects;           // N x cells
  Eigen::MatrixXd templates;         // M x cells (0 rows for the flat model)
  Eigen::MatrixXd correspondences;   // snapshots x N, E[c_s = n]
  Eigen::MatrixXd responsibilities;  // N x M, E[z_n = m] (0 columns for the flat model)
  std::vector<Alignment> alignments;
  std::vector<int> snapshot_object;  // MAP injective assignment per map
  std::vector<int> object_template;  // MAP template per object (empty for flat)
  double log_likelihood = 0.0;       // log p(data, model | delta) at the final sigma, tau
  int iterations = 0;
  bool approximate = false;  // the sampled E-step was used for some map
};

// f(mu_s, delta_s) for every snapshot, one row each.
Eigen::MatrixXd AlignedMatrix(const EmProblem& problem, const std::vector<Alignment>& alignments);

// -|f(mu_s, delta_s) - theta_n|^2 / (2 sigma^2), snapshots x N (no normalising constant).
Eigen::MatrixXd SnapshotLogLikelihoods(const Eigen::MatrixXd& aligned,
                                       const Eigen::MatrixXd& objects, double sigma);

struct CorrespondenceStep {
  Eigen::MatrixXd expectations;  // snapshots x N
  // sum_t [log sum_a prod_k p(mu_k | theta_a(k)) - log #assignments]: the data log-likelihood
  // under the uniform prior over injective assignments, without the Gaussian constants.
  double log_likelihood = 0.0;
  bool approximate = false;
};

// The E-step over every map; maps with more than options.max_exact_snapshots snapshots are
// sampled (Gibbs) with `random`.
CorrespondenceStep CorrespondenceEStep(const EmProblem& problem,
                                       const Eigen::MatrixXd& log_likelihoods,
                                       const EmOptions& options, std::mt19937_64* random);

// MAP assignment per map (exact DP, or greedy above the bound).
std::vector<int> MapAssignments(const EmProblem& problem, const Eigen::MatrixXd& log_likelihoods,
                                const EmOptions& options);

// The alignment M-step for every snapshot, against theta_bar_s = sum_n E[c_s = n] theta_n.
void AlignmentStep(const EmProblem& problem, const Eigen::MatrixXd& correspondences,
                   const Eigen::MatrixXd& objects, bool scan_rotations, const EmOptions& options,
                   std::vector<Alignment>* alignments);

// A random start: N distinct snapshots (drawn with `random`) become the objects; every snapshot is
// aligned, by a rotation scan, to the object it then matches best.
void RandomStart(const EmProblem& problem, int num_objects, const EmOptions& options,
                 std::mt19937_64* random, Eigen::MatrixXd* objects,
                 std::vector<Alignment>* alignments);

// The Gaussian normalising constant of `count` cells: -count * log(sqrt(2 pi) s).
double GaussianLogConstant(double count, double s);

// The annealed noise of iteration j (eqs. 27, 28): max(final, initial * kappa^j).
double Annealed(double final_value, double initial_value, double kappa, int j);

}  // namespace fleetmap::object_learning

#include "common/object_learning/snapshot_extractor.hpp"

namespace fleetmap::object_learning {

// The EM's view of extracted snapshots: their patches, grouped by map.
EmProblem MakeEmProblem(const SnapshotSet& set);

}  // namespace fleetmap::object_learning
