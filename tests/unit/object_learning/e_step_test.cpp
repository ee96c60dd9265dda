#include "common/object_learning/e_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fleetmap::object_learning {
namespace {

Eigen::MatrixXd RandomLogLikelihood(int k, int n, uint64_t seed, double scale) {
  std::mt19937_64 random(seed);
  Eigen::MatrixXd m(k, n);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < n; ++j) m(i, j) = scale * (UniformDouble(&random) - 0.5);
  }
  return m;
}

TEST(EStepTest, ExactEqualsBruteForceEnumeration) {
  for (const auto& [k, n] : {std::pair{1, 1}, {2, 3}, {3, 3}, {3, 5}, {4, 6}, {5, 5}}) {
    for (uint64_t seed = 0; seed < 4; ++seed) {
      const Eigen::MatrixXd ll = RandomLogLikelihood(k, n, seed, 20.0);
      const CorrespondenceExpectations exact = ExactCorrespondences(ll);
      const CorrespondenceExpectations brute = EnumeratedCorrespondences(ll);
      EXPECT_NEAR(exact.log_normalizer, brute.log_normalizer, 1e-9) << k << " x " << n;
      EXPECT_TRUE(exact.expectations.isApprox(brute.expectations, 1e-9)) << k << " x " << n;
      for (int i = 0; i < k; ++i) EXPECT_NEAR(exact.expectations.row(i).sum(), 1.0, 1e-9);
      // Each object holds at most one snapshot in expectation.
      for (int j = 0; j < n; ++j) EXPECT_LE(exact.expectations.col(j).sum(), 1.0 + 1e-9);
    }
  }
}

TEST(EStepTest, MutualExclusionKeepsTwoSnapshotsOffOneObject) {
  // Both snapshots of this map prefer object 0 by far; they cannot both be object 0.
  Eigen::MatrixXd ll(2, 3);
  ll << 0.0, -50.0, -100.0,  //
      0.0, -50.0, -100.0;
  const CorrespondenceExpectations e = ExactCorrespondences(ll);
  EXPECT_NEAR(e.expectations(0, 0), 0.5, 1e-9);
  EXPECT_NEAR(e.expectations(1, 0), 0.5, 1e-9);
  EXPECT_NEAR(e.expectations(0, 1), 0.5, 1e-9);
  EXPECT_NEAR(e.expectations.col(0).sum(), 1.0, 1e-9);
  // Without the constraint each row's softmax would put ~1 on object 0.
  const Eigen::MatrixXd independent = Responsibilities(ll);
  EXPECT_GT(independent(0, 0), 0.999);
  EXPECT_GT(independent(1, 0), 0.999);
  EXPECT_EQ(BestAssignment(ll)[0] + BestAssignment(ll)[1], 1);  // objects 0 and 1
}

TEST(EStepTest, LogSpaceSurvivesHugeLikelihoods) {
  Eigen::MatrixXd ll = RandomLogLikelihood(4, 6, 7, 1.0);
  ll.array() -= 1e5;  // exp() of these underflows to 0 in double
  const CorrespondenceExpectations e = ExactCorrespondences(ll);
  EXPECT_TRUE(std::isfinite(e.log_normalizer));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(e.expectations.row(i).sum(), 1.0, 1e-9);
}

TEST(EStepTest, TooFewObjectsHaveNoAssignment) {
  const CorrespondenceExpectations e = ExactCorrespondences(Eigen::MatrixXd::Zero(3, 2));
  EXPECT_TRUE(std::isinf(e.log_normalizer));
  EXPECT_LT(e.log_normalizer, 0.0);
}

TEST(EStepTest, BestAssignmentIsTheMostProbableInjectiveOne) {
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const Eigen::MatrixXd ll = RandomLogLikelihood(4, 5, seed, 10.0);
    const std::vector<int> best = BestAssignment(ll);
    double best_weight = 0.0;
    for (int k = 0; k < 4; ++k) best_weight += ll(k, best[k]);
    // Every injective assignment weighs at most as much.
    std::vector<int> a(4);
    for (a[0] = 0; a[0] < 5; ++a[0])
      for (a[1] = 0; a[1] < 5; ++a[1])
        for (a[2] = 0; a[2] < 5; ++a[2])
          for (a[3] = 0; a[3] < 5; ++a[3]) {
            bool injective = true;
            for (int i = 0; i < 4; ++i)
              for (int j = i + 1; j < 4; ++j) injective = injective && a[i] != a[j];
            if (!injective) continue;
            double w = 0.0;
            for (int k = 0; k < 4; ++k) w += ll(k, a[k]);
            EXPECT_LE(w, best_weight + 1e-9);
          }
  }
}

TEST(EStepTest, GibbsSamplingApproximatesTheExactMarginals) {
  const Eigen::MatrixXd ll = RandomLogLikelihood(5, 6, 3, 3.0);
  std::mt19937_64 random(42);
  const CorrespondenceExpectations sampled = SampledCorrespondences(ll, 20000, 200, &random);
  const CorrespondenceExpectations exact = ExactCorrespondences(ll);
  EXPECT_LT((sampled.expectations - exact.expectations).cwiseAbs().maxCoeff(), 0.03);
  EXPECT_LE(sampled.log_normalizer, exact.log_normalizer);  // a lower bound
}

TEST(EStepTest, ResponsibilitiesAreASoftmaxPerObject) {
  Eigen::MatrixXd w(2, 2);
  w << 0.0, std::log(3.0),  //
      -1000.0, 0.0;
  const Eigen::MatrixXd r = Responsibilities(w);
  EXPECT_NEAR(r(0, 0), 0.25, 1e-12);
  EXPECT_NEAR(r(0, 1), 0.75, 1e-12);
  EXPECT_NEAR(r(1, 1), 1.0, 1e-12);
}

}  // namespace
}  // namespace fleetmap::object_learning
