#pragma once

// What hierarchical and flat EM share: the snapshots grouped by map, the aligned snapshots, the
// snapshot-object log-likelihoods (eq. 1), the correspondence E-step over all maps (exact or
// sampled, eq. 19), the alignment M-step (eq. 26), and the random start.
//
// Alignments are kept per (snapshot, object) pair, delta_s,n, rather than one per snapshot as in
// the paper: the E-step then compares each snapshot with each object at its best alignment to
// that object. With a single delta_s (aligned to the expected object), a snapshot aligned to the
// wrong object is judged against the right one at the wrong alignment and stays where it is; on
// partial views (a chair seen from one side) this locked runs into poor local maxima
// (docs/object-learning.md has the measurements). Q (eq. 18) is unchanged but for delta_s
// becoming delta_s,n, and each delta_s,n minimises |f(mu_s, delta) - theta_n|^2 by itself.
//
// Thread-safety: an EmProblem is immutable once built; the functions are stateless.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "common/object_learning/alignment.hpp"
#include "common/object_learning/learn_options.hpp"
#include "common/object_learning/snapshot_extractor.hpp"

namespace fleetmap::object_learning {

struct EmProblem {
  std::vector<scene::Patch> snapshots;  // all of one size
  std::vector<std::vector<int>> maps;   // snapshot indices of each map (K_t = maps[t].size())
  int cells() const { return snapshots.empty() ? 0 : snapshots[0].width * snapshots[0].height; }
  int max_per_map() const;
};

// The model and correspondences one EM run ends with.
struct EmResult {
  Eigen::MatrixXd objects;           // N x cells
  Eigen::MatrixXd templates;         // M x cells (0 rows for the flat model)
  Eigen::MatrixXd correspondences;   // snapshots x N, E[c_s = n]
  Eigen::MatrixXd responsibilities;  // N x M, E[z_n = m] (0 columns for the flat model)
  std::vector<std::vector<Alignment>> alignments;  // [snapshot][object], delta_s,n
  std::vector<int> snapshot_object;                // MAP injective assignment per map
  std::vector<int> object_template;                // MAP template per object (empty for flat)
  double log_likelihood = 0.0;  // log p(data, model | delta) at the final sigma, tau
  int iterations = 0;
  bool approximate = false;  // the sampled E-step was used for some map
};

using PairAlignments = std::vector<std::vector<Alignment>>;  // [snapshot][object]

// The EM's view of extracted snapshots: their patches, grouped by map.
EmProblem MakeEmProblem(const SnapshotSet& set);

// The data side of the EM works on f(mu_s, delta_s,n), the snapshots resampled under their pair
// alignments, with the moved observed-cell weights w_s,n. They are resampled pair by pair and
// dropped at once rather than held as one snapshots x cells matrix per object: that table grows as
// snapshots x objects x cells (4.5 GB for 160 snapshots, 40 objects and 211 x 211 patches, issue
// 22), while streaming needs one patch of scratch and keeps memory linear in snapshots x cells.

// -sum_x w (f(mu_s, delta_s,n) - theta_n)^2 / (2 sigma^2), snapshots x N (no normalising
// constant): unobserved cells are missing data and drop out.
Eigen::MatrixXd SnapshotLogLikelihoods(const EmProblem& problem, const PairAlignments& alignments,
                                       const Eigen::MatrixXd& objects, double sigma);

// sum_s E[c_s = n] (w f + (1 - w) theta_n), N x cells: the data side of the M-step, unobserved
// cells imputed with their expectation under the current object (EM for missing data), which
// keeps the M-step's matrix the same for every cell. Pairs with E[c_s = n] < 1e-9 are skipped.
Eigen::MatrixXd WeightedSnapshotSums(const EmProblem& problem, const PairAlignments& alignments,
                                     const Eigen::MatrixXd& correspondences,
                                     const Eigen::MatrixXd& objects);

// Observed cells of all snapshots (sum of their weights), for the Gaussian constant.
double ObservedCells(const EmProblem& problem);

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

// The alignment M-step: every pair with E[c_s = n] above a small threshold climbs from its
// current alignment; with `all_pairs` every pair is re-aligned from a rotation scan (so pairs
// that carry no weight now are ready when the E-step next looks at them).
void AlignmentStep(const EmProblem& problem, const Eigen::MatrixXd& correspondences,
                   const Eigen::MatrixXd& objects, bool all_pairs, const EmOptions& options,
                   PairAlignments* alignments);

// A random start: N distinct snapshots (drawn with `random`) become the objects; every snapshot is
// aligned to every object by a rotation scan and one coarse climb.
void RandomStart(const EmProblem& problem, int num_objects, const EmOptions& options,
                 std::mt19937_64* random, Eigen::MatrixXd* objects, PairAlignments* alignments);

// The MAP object's alignment of every snapshot.
std::vector<Alignment> AssignedAlignments(const PairAlignments& alignments,
                                          const std::vector<int>& snapshot_object);

// The Gaussian normalising constant of `count` cells: -count * log(sqrt(2 pi) s).
double GaussianLogConstant(double count, double s);

// The annealed noise of iteration j (eqs. 27, 28): max(final, initial * kappa^j).
double Annealed(double final_value, double initial_value, double kappa, int j);

}  // namespace fleetmap::object_learning
