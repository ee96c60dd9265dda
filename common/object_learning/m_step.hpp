#pragma once

// The model M-step of ALGORITHMS.md 2 (eqs. 21-25). For fixed expectations C (snapshots x
// objects), Z (objects x templates) and aligned snapshots, the expected log-likelihood decouples
// over cells; for every cell x the N + M unknowns v = (theta_1[x]..theta_N[x], alpha_1[x]..
// alpha_M[x]) minimise
//   sum_n,m Z[n,m] (theta_n - alpha_m)^2 / tau^2 + sum_s,n C[s,n] (mu_s[x] - theta_n)^2 / sigma^2,
// whose normal equations A v = b have a matrix A that depends only on C and Z. A is factored once
// (LDLT) and solved for every cell at once, the right-hand sides as the columns of one matrix.
// A template that no object uses would make A singular: a tiny ridge keeps it at its old value.
//
// Thread-safety: stateless.

#include <Eigen/Core>

namespace fleetmap::object_learning {

struct HierarchicalParameters {
  Eigen::MatrixXd objects;    // N x cells, theta
  Eigen::MatrixXd templates;  // M x cells, alpha
};

// The normal-equation matrix A ((N + M) x (N + M)), exposed for tests.
Eigen::MatrixXd NormalMatrix(const Eigen::MatrixXd& correspondences,
                             const Eigen::MatrixXd& responsibilities, double sigma, double tau,
                             double ridge);

// `snapshot_sums` is N x cells, row n = sum_s C[s,n] f(mu_s, delta_s,n) (the right-hand sides
// before scaling), `correspondences` is snapshots x N, `responsibilities` is N x M;
// `previous_templates` (M x cells) anchors the ridge.
HierarchicalParameters HierarchicalMStep(const Eigen::MatrixXd& snapshot_sums,
                                         const Eigen::MatrixXd& correspondences,
                                         const Eigen::MatrixXd& responsibilities, double sigma,
                                         double tau, const Eigen::MatrixXd& previous_templates);

// The flat model's M-step (Biswas et al. 2002): each object is the C-weighted mean of its aligned
// snapshots (snapshot_sums row / weight); an object with (almost) no weight keeps its previous
// value.
Eigen::MatrixXd FlatMStep(const Eigen::MatrixXd& snapshot_sums,
                          const Eigen::MatrixXd& correspondences,
                          const Eigen::MatrixXd& previous_objects);

}  // namespace fleetmap::object_learning
