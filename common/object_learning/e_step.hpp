#pragma once

// The E-step of ALGORITHMS.md 2, in log space.
//  - Correspondences of one map's snapshots to objects under mutual exclusion (eq. 19): the
//    distribution over injective assignments a (snapshot k -> object a(k), no object twice) with
//    weight prod_k exp(log_likelihood(k, a(k))). Exact: a dynamic programme over the objects and
//    the subsets of snapshots (forward and backward sums), O(N K 2^K) instead of the N! / (N - K)!
//    assignments, so it is exact for K up to EmOptions::max_exact_snapshots. Above that, Gibbs
//    sampling over injective assignments approximates the marginals.
//  - Responsibilities of templates for objects (eq. 20): a softmax per object.
//
// Thread-safety: stateless (the sampler's generator is passed in).

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

namespace fleetmap::object_learning {

struct CorrespondenceExpectations {
  Eigen::MatrixXd expectations;  // K x N, E[c_k = n]; each row sums to 1
  // log sum over injective assignments of prod_k exp(log_likelihood(k, a(k))); -inf when N < K.
  // The Gibbs sampler reports the best sampled assignment's log weight (a lower bound).
  double log_normalizer = 0.0;
};

// Exact. `log_likelihood` is K x N (K <= 20, the DP has 2^K states per object). N < K: no
// injective assignment exists; expectations are zero and log_normalizer is -inf.
CorrespondenceExpectations ExactCorrespondences(const Eigen::MatrixXd& log_likelihood);

// Gibbs sampling over injective assignments: each sweep resamples every snapshot's object among
// those no other snapshot holds, from its exact conditional. `burn_in` sweeps are dropped, then
// `sweeps` are averaged. Requires N >= K.
CorrespondenceExpectations SampledCorrespondences(const Eigen::MatrixXd& log_likelihood, int sweeps,
                                                  int burn_in, std::mt19937_64* random);

// The brute-force sum over every injective assignment, for tests (and K, N tiny).
CorrespondenceExpectations EnumeratedCorrespondences(const Eigen::MatrixXd& log_likelihood);

// Row-wise softmax of `log_weights` (rows: objects, columns: templates): E[z_n = m].
Eigen::MatrixXd Responsibilities(const Eigen::MatrixXd& log_weights);

// log sum exp of a row.
double LogSumExp(const Eigen::Ref<const Eigen::VectorXd>& values);

// log(N! / (N - K)!): how many injective assignments there are (log of the uniform prior's
// denominator).
double LogInjectiveCount(int num_objects, int num_snapshots);

// Uniform in [0, 1) from 53 bits of the generator (std::uniform_real_distribution differs between
// standard libraries).
double UniformDouble(std::mt19937_64* random);

}  // namespace fleetmap::object_learning

namespace fleetmap::object_learning {

// The most probable injective assignment (max-product over the same subset DP as
// ExactCorrespondences): assignment[k] is snapshot k's object. K <= 20 and N >= K.
std::vector<int> BestAssignment(const Eigen::MatrixXd& log_likelihood);

// Greedy: the strongest (snapshot, object) pairs first, each snapshot and object used once; for
// maps above the exact bound. Requires N >= K.
std::vector<int> GreedyAssignment(const Eigen::MatrixXd& log_likelihood);

}  // namespace fleetmap::object_learning
