#pragma once

// The test-set log-likelihood of the paper's cross-validation: how well learned objects explain
// the snapshots of a map that was held out of training. Each held-out snapshot is aligned to each
// object (rotation scan, then hill climbing: alignments are parameters, maximised), and the
// correspondences are summed out exactly under mutual exclusion with the uniform prior:
//   log p(mu_t | theta) = log sum_a prod_k N(f(mu_k, delta_k,a(k)); theta_a(k), sigma^2 I)
//                         - log #injective assignments.
//
// Thread-safety: stateless.

#include <Eigen/Core>
#include <vector>

#include "common/object_learning/alignment.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

// `snapshots` are one map's (all of the objects' patch size); `objects` is N x cells with
// N >= snapshots.size(). Uses options.sigma (the final noise level).
double HeldOutLogLikelihood(const std::vector<scene::Patch>& snapshots,
                            const Eigen::MatrixXd& objects, const EmOptions& options);

}  // namespace fleetmap::object_learning
