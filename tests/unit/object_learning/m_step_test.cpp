#include "common/object_learning/m_step.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "common/object_learning/e_step.hpp"

namespace fleetmap::object_learning {
namespace {

Eigen::MatrixXd RandomStochastic(int rows, int cols, std::mt19937_64* random) {
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) m(i, j) = 0.05 + UniformDouble(random);
    m.row(i) /= m.row(i).sum();
  }
  return m;
}

// The cell's problem written out as a weighted least-squares system, one row per term:
// sqrt(Z[n,m]) (theta_n - alpha_m) / tau and sqrt(C[s,n]) (theta_n - mu_s) / sigma.
Eigen::VectorXd DirectSolve(const Eigen::MatrixXd& c, const Eigen::MatrixXd& z,
                            const Eigen::VectorXd& mu, double sigma, double tau) {
  const int s_count = c.rows(), n = z.rows(), m = z.cols();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n * m + s_count * n, n + m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(a.rows());
  int row = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j, ++row) {
      a(row, i) = std::sqrt(z(i, j)) / tau;
      a(row, n + j) = -std::sqrt(z(i, j)) / tau;
    }
  }
  for (int s = 0; s < s_count; ++s) {
    for (int i = 0; i < n; ++i, ++row) {
      a(row, i) = std::sqrt(c(s, i)) / sigma;
      b(row) = std::sqrt(c(s, i)) * mu(s) / sigma;
    }
  }
  return a.colPivHouseholderQr().solve(b);
}

TEST(MStepTest, HierarchicalEqualsDirectLeastSquaresPerCell) {
  std::mt19937_64 random(5);
  const int snapshots = 7, n = 4, m = 2, cells = 9;
  const Eigen::MatrixXd c = RandomStochastic(snapshots, n, &random);
  const Eigen::MatrixXd z = RandomStochastic(n, m, &random);
  Eigen::MatrixXd aligned(snapshots, cells);
  for (int s = 0; s < snapshots; ++s) {
    for (int x = 0; x < cells; ++x) aligned(s, x) = UniformDouble(&random);
  }
  const double sigma = 0.3, tau = 0.2;
  const HierarchicalParameters p =
      HierarchicalMStep(c.transpose() * aligned, c, z, sigma, tau, Eigen::MatrixXd::Zero(m, cells));
  for (int x = 0; x < cells; ++x) {
    const Eigen::VectorXd v = DirectSolve(c, z, aligned.col(x), sigma, tau);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(p.objects(i, x), v(i), 1e-5) << "cell " << x;
    for (int j = 0; j < m; ++j) EXPECT_NEAR(p.templates(j, x), v(n + j), 1e-5) << "cell " << x;
  }
}

TEST(MStepTest, NormalMatrixDependsOnlyOnExpectations) {
  std::mt19937_64 random(9);
  const Eigen::MatrixXd c = RandomStochastic(5, 3, &random);
  const Eigen::MatrixXd z = RandomStochastic(3, 2, &random);
  const Eigen::MatrixXd a = NormalMatrix(c, z, 0.5, 0.25, 0.0);
  EXPECT_TRUE(a.isApprox(a.transpose()));
  // Positive definite: every template has objects, every object has snapshots.
  EXPECT_EQ(Eigen::LDLT<Eigen::MatrixXd>(a).info(), Eigen::Success);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().minCoeff(), 0.0);
}

TEST(MStepTest, UnusedTemplateStaysWhereItWas) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd z(2, 2);
  z << 1.0, 0.0,  //
      1.0, 0.0;
  Eigen::MatrixXd aligned(2, 3);
  aligned << 1.0, 0.0, 1.0,  //
      0.0, 1.0, 1.0;
  Eigen::MatrixXd previous(2, 3);
  previous << 0.0, 0.0, 0.0,  //
      0.7, 0.7, 0.7;
  const HierarchicalParameters p =
      HierarchicalMStep(c.transpose() * aligned, c, z, 0.3, 0.3, previous);
  EXPECT_TRUE(p.templates.row(1).isApprox(previous.row(1), 1e-4));
  EXPECT_NEAR(p.templates(0, 2), 1.0, 1e-5);  // both objects are 1 there (the ridge aside)
}

TEST(MStepTest, FlatIsTheWeightedMean) {
  Eigen::MatrixXd c(3, 2);
  c << 1.0, 0.0,  //
      0.5, 0.5,   //
      0.0, 1.0;
  Eigen::MatrixXd aligned(3, 2);
  aligned << 1.0, 0.0,  //
      0.0, 1.0,         //
      1.0, 1.0;
  const Eigen::MatrixXd objects =
      FlatMStep(c.transpose() * aligned, c, Eigen::MatrixXd::Zero(2, 2));
  EXPECT_NEAR(objects(0, 0), 1.0 / 1.5, 1e-12);
  EXPECT_NEAR(objects(0, 1), 0.5 / 1.5, 1e-12);
  EXPECT_NEAR(objects(1, 0), 1.0 / 1.5, 1e-12);
  EXPECT_NEAR(objects(1, 1), 1.5 / 1.5, 1e-12);
}

}  // namespace
}  // namespace fleetmap::object_learning
