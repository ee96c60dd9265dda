#include "common/object_learning/e_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "common/core/check.hpp"

namespace fleetmap::object_learning {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

double LogAdd(double a, double b) {
  if (a == kNegInf) return b;
  if (b == kNegInf) return a;
  const double m = std::max(a, b);
  return m + std::log1p(std::exp(-std::abs(a - b)));
}

}  // namespace

double LogSumExp(const Eigen::Ref<const Eigen::VectorXd>& values) {
  if (values.size() == 0) return kNegInf;
  const double m = values.maxCoeff();
  if (m == kNegInf) return kNegInf;
  return m + std::log((values.array() - m).exp().sum());
}

double LogInjectiveCount(int num_objects, int num_snapshots) {
  double sum = 0.0;
  for (int i = 0; i < num_snapshots; ++i) sum += std::log(static_cast<double>(num_objects - i));
  return sum;
}

double UniformDouble(std::mt19937_64* random) {
  return static_cast<double>((*random)() >> 11) * 0x1.0p-53;
}

CorrespondenceExpectations ExactCorrespondences(const Eigen::MatrixXd& log_likelihood) {
  const int k_count = static_cast<int>(log_likelihood.rows());
  const int n_count = static_cast<int>(log_likelihood.cols());
  FLEETMAP_CHECK(k_count <= 20);
  CorrespondenceExpectations result;
  result.expectations = Eigen::MatrixXd::Zero(k_count, n_count);
  if (k_count == 0) return result;
  if (n_count < k_count) {
    result.log_normalizer = kNegInf;
    return result;
  }
  const size_t subsets = size_t{1} << k_count;
  const size_t all = subsets - 1;
  // forward[n][S]: log-sum over injective maps of the snapshots in S into objects 0..n-1.
  // backward[n][S]: the same into objects n..N-1.
  std::vector<std::vector<double>> forward(n_count + 1, std::vector<double>(subsets, kNegInf));
  std::vector<std::vector<double>> backward(n_count + 1, std::vector<double>(subsets, kNegInf));
  forward[0][0] = 0.0;
  for (int n = 0; n < n_count; ++n) {
    const std::vector<double>& in = forward[n];
    std::vector<double>& out = forward[n + 1];
    for (size_t s = 0; s < subsets; ++s) {
      double value = in[s];  // object n unused
      for (int k = 0; k < k_count; ++k) {
        const size_t bit = size_t{1} << k;
        if ((s & bit) && in[s ^ bit] != kNegInf) {
          value = LogAdd(value, in[s ^ bit] + log_likelihood(k, n));
        }
      }
      out[s] = value;
    }
  }
  backward[n_count][0] = 0.0;
  for (int n = n_count - 1; n >= 0; --n) {
    const std::vector<double>& in = backward[n + 1];
    std::vector<double>& out = backward[n];
    for (size_t s = 0; s < subsets; ++s) {
      double value = in[s];
      for (int k = 0; k < k_count; ++k) {
        const size_t bit = size_t{1} << k;
        if ((s & bit) && in[s ^ bit] != kNegInf) {
          value = LogAdd(value, in[s ^ bit] + log_likelihood(k, n));
        }
      }
      out[s] = value;
    }
  }
  result.log_normalizer = forward[n_count][all];
  const double log_z = result.log_normalizer;
  for (int n = 0; n < n_count; ++n) {
    for (int k = 0; k < k_count; ++k) {
      const size_t bit = size_t{1} << k;
      double value = kNegInf;
      // Snapshots in S go to objects before n, k to n, the rest to objects after n.
      for (size_t s = 0; s < subsets; ++s) {
        if (s & bit) continue;
        const double f = forward[n][s];
        if (f == kNegInf) continue;
        const double b = backward[n + 1][all ^ s ^ bit];
        if (b == kNegInf) continue;
        value = LogAdd(value, f + b);
      }
      if (value != kNegInf) {
        result.expectations(k, n) = std::exp(value + log_likelihood(k, n) - log_z);
      }
    }
  }
  return result;
}

CorrespondenceExpectations EnumeratedCorrespondences(const Eigen::MatrixXd& log_likelihood) {
  const int k_count = static_cast<int>(log_likelihood.rows());
  const int n_count = static_cast<int>(log_likelihood.cols());
  CorrespondenceExpectations result;
  result.expectations = Eigen::MatrixXd::Zero(k_count, n_count);
  result.log_normalizer = k_count == 0 ? 0.0 : kNegInf;
  if (k_count == 0 || n_count < k_count) return result;
  std::vector<std::pair<std::vector<int>, double>> terms;
  std::vector<int> assignment(k_count, 0);
  std::vector<bool> used(n_count, false);
  // Depth-first over injective assignments.
  auto recurse = [&](auto&& self, int k, double log_weight) -> void {
    if (k == k_count) {
      terms.emplace_back(assignment, log_weight);
      result.log_normalizer = LogAdd(result.log_normalizer, log_weight);
      return;
    }
    for (int n = 0; n < n_count; ++n) {
      if (used[n]) continue;
      used[n] = true;
      assignment[k] = n;
      self(self, k + 1, log_weight + log_likelihood(k, n));
      used[n] = false;
    }
  };
  recurse(recurse, 0, 0.0);
  for (const auto& [a, w] : terms) {
    const double p = std::exp(w - result.log_normalizer);
    for (int k = 0; k < k_count; ++k) result.expectations(k, a[k]) += p;
  }
  return result;
}

CorrespondenceExpectations SampledCorrespondences(const Eigen::MatrixXd& log_likelihood, int sweeps,
                                                  int burn_in, std::mt19937_64* random) {
  const int k_count = static_cast<int>(log_likelihood.rows());
  const int n_count = static_cast<int>(log_likelihood.cols());
  FLEETMAP_CHECK(n_count >= k_count);
  CorrespondenceExpectations result;
  result.expectations = Eigen::MatrixXd::Zero(k_count, n_count);
  if (k_count == 0) return result;
  std::vector<int> assignment = GreedyAssignment(log_likelihood);
  std::vector<int> holder(n_count, -1);
  for (int k = 0; k < k_count; ++k) holder[assignment[k]] = k;
  auto log_weight = [&]() {
    double w = 0.0;
    for (int k = 0; k < k_count; ++k) w += log_likelihood(k, assignment[k]);
    return w;
  };
  double best = log_weight();
  std::vector<double> conditional(n_count);
  for (int sweep = 0; sweep < burn_in + sweeps; ++sweep) {
    for (int k = 0; k < k_count; ++k) {
      holder[assignment[k]] = -1;
      double m = -std::numeric_limits<double>::infinity();
      for (int n = 0; n < n_count; ++n) {
        conditional[n] = holder[n] < 0 ? log_likelihood(k, n) : kNegInf;
        m = std::max(m, conditional[n]);
      }
      double total = 0.0;
      for (int n = 0; n < n_count; ++n) {
        conditional[n] = conditional[n] == kNegInf ? 0.0 : std::exp(conditional[n] - m);
        total += conditional[n];
      }
      double u = UniformDouble(random) * total;
      int chosen = -1;
      for (int n = 0; n < n_count; ++n) {
        if (conditional[n] <= 0.0) continue;
        chosen = n;
        if (u < conditional[n]) break;
        u -= conditional[n];
      }
      assignment[k] = chosen;
      holder[chosen] = k;
    }
    if (sweep >= burn_in) {
      for (int k = 0; k < k_count; ++k) result.expectations(k, assignment[k]) += 1.0;
      best = std::max(best, log_weight());
    }
  }
  result.expectations /= std::max(1, sweeps);
  result.log_normalizer = best;
  return result;
}

std::vector<int> GreedyAssignment(const Eigen::MatrixXd& log_likelihood) {
  const int k_count = static_cast<int>(log_likelihood.rows());
  const int n_count = static_cast<int>(log_likelihood.cols());
  FLEETMAP_CHECK(n_count >= k_count);
  std::vector<int> assignment(k_count, -1);
  std::vector<bool> used(n_count, false);
  std::vector<std::pair<double, std::pair<int, int>>> pairs;
  for (int k = 0; k < k_count; ++k) {
    for (int n = 0; n < n_count; ++n) pairs.push_back({-log_likelihood(k, n), {k, n}});
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [cost, kn] : pairs) {
    if (assignment[kn.first] < 0 && !used[kn.second]) {
      assignment[kn.first] = kn.second;
      used[kn.second] = true;
    }
  }
  return assignment;
}

std::vector<int> BestAssignment(const Eigen::MatrixXd& log_likelihood) {
  const int k_count = static_cast<int>(log_likelihood.rows());
  const int n_count = static_cast<int>(log_likelihood.cols());
  FLEETMAP_CHECK(k_count <= 20 && n_count >= k_count);
  if (k_count == 0) return {};
  const size_t subsets = size_t{1} << k_count;
  // best[n][S]: the best log weight of an injective map of S into objects 0..n-1; choice[n][S]:
  // the snapshot object n-1 took (-1: none).
  std::vector<std::vector<double>> best(n_count + 1, std::vector<double>(subsets, kNegInf));
  std::vector<std::vector<int8_t>> choice(n_count + 1, std::vector<int8_t>(subsets, -1));
  best[0][0] = 0.0;
  for (int n = 0; n < n_count; ++n) {
    for (size_t s = 0; s < subsets; ++s) {
      double value = best[n][s];
      int8_t taken = -1;
      for (int k = 0; k < k_count; ++k) {
        const size_t bit = size_t{1} << k;
        if (!(s & bit) || best[n][s ^ bit] == kNegInf) continue;
        const double candidate = best[n][s ^ bit] + log_likelihood(k, n);
        if (candidate > value) {
          value = candidate;
          taken = static_cast<int8_t>(k);
        }
      }
      best[n + 1][s] = value;
      choice[n + 1][s] = taken;
    }
  }
  std::vector<int> assignment(k_count, -1);
  size_t s = subsets - 1;
  for (int n = n_count; n > 0; --n) {
    const int k = choice[n][s];
    if (k >= 0) {
      assignment[k] = n - 1;
      s ^= size_t{1} << k;
    }
  }
  return assignment;
}

Eigen::MatrixXd Responsibilities(const Eigen::MatrixXd& log_weights) {
  Eigen::MatrixXd out(log_weights.rows(), log_weights.cols());
  for (Eigen::Index r = 0; r < log_weights.rows(); ++r) {
    const double m = log_weights.row(r).maxCoeff();
    out.row(r) = (log_weights.row(r).array() - m).exp();
    out.row(r) /= out.row(r).sum();
  }
  return out;
}

}  // namespace fleetmap::object_learning
