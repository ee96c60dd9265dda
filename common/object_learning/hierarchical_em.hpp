#pragma once

// One run of hierarchical EM (ALGORITHMS.md 2) for a fixed number of objects N and templates M,
// from one random start: E-step (correspondences under mutual exclusion, template
// responsibilities), closed-form model M-step, alignment M-step, with sigma and tau annealed
// from their initial to their final values. Ends with the log joint p(data, theta, alpha | delta)
// at the final sigma and tau (c and z summed out under uniform priors), for model selection.
// Beyond the paper (docs/object-learning.md, "Design choices"): objects are aligned to templates
// and re-framed onto their most likely one each iteration, and at rotation-scan iterations the
// templates are regrouped by k-medoids over the objects when that explains them clearly better.
//
// Thread-safety: stateless; runs may go concurrently.

#include <cstdint>
#include <functional>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

// Requires 1 <= M <= N, N >= problem.max_per_map(), N <= number of snapshots.
// `on_iteration`, when set, is called after each EM iteration with the iterations done.
EmResult RunHierarchicalEm(const EmProblem& problem, int num_objects, int num_templates,
                           const EmOptions& options, uint64_t seed,
                           const std::function<void(int)>& on_iteration = {});

// The object level of the log joint, sum_n log((1 / M) sum_m N(theta_n; alpha_m, tau^2 I)),
// from log_weights(n, m) = -|theta_n - alpha_m|^2 / (2 tau^2) (objects aligned to templates)
// over `cells` cells.
double ObjectLevelLogLikelihood(const Eigen::MatrixXd& log_weights, Eigen::Index cells, double tau);

}  // namespace fleetmap::object_learning
