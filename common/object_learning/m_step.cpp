#include "common/object_learning/m_step.hpp"

#include <Eigen/Cholesky>

#include "common/core/check.hpp"

namespace fleetmap::object_learning {
namespace {

// Relative to 1 / tau^2: small enough not to move a used template measurably, large enough to
// make A positive definite when a template has no object.
constexpr double kRidge = 1e-6;

}  // namespace

Eigen::MatrixXd NormalMatrix(const Eigen::MatrixXd& correspondences,
                             const Eigen::MatrixXd& responsibilities, double sigma, double tau,
                             double ridge) {
  const Eigen::Index n = responsibilities.rows();
  const Eigen::Index m = responsibilities.cols();
  const double ws = 1.0 / (sigma * sigma);
  const double wt = 1.0 / (tau * tau);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + m, n + m);
  const Eigen::VectorXd snapshot_mass = correspondences.colwise().sum().transpose();  // per object
  const Eigen::VectorXd object_mass = responsibilities.colwise().sum().transpose();  // per template
  for (Eigen::Index i = 0; i < n; ++i) {
    a(i, i) = wt * responsibilities.row(i).sum() + ws * snapshot_mass(i);
  }
  for (Eigen::Index j = 0; j < m; ++j) a(n + j, n + j) = wt * object_mass(j) + ridge;
  a.topRightCorner(n, m) = -wt * responsibilities;
  a.bottomLeftCorner(m, n) = -wt * responsibilities.transpose();
  return a;
}

HierarchicalParameters HierarchicalMStep(const Eigen::MatrixXd& snapshot_sums,
                                         const Eigen::MatrixXd& correspondences,
                                         const Eigen::MatrixXd& responsibilities, double sigma,
                                         double tau, const Eigen::MatrixXd& previous_templates) {
  const Eigen::Index n = responsibilities.rows();
  const Eigen::Index m = responsibilities.cols();
  FLEETMAP_CHECK(correspondences.cols() == n && snapshot_sums.rows() == n);
  FLEETMAP_CHECK(previous_templates.rows() == m &&
                 previous_templates.cols() == snapshot_sums.cols());
  const double ridge = kRidge / (tau * tau);
  const Eigen::MatrixXd a = NormalMatrix(correspondences, responsibilities, sigma, tau, ridge);
  // Right-hand sides, one column per cell.
  Eigen::MatrixXd b(n + m, snapshot_sums.cols());
  b.topRows(n) = snapshot_sums / (sigma * sigma);
  b.bottomRows(m) = ridge * previous_templates;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  const Eigen::MatrixXd v = ldlt.solve(b);
  return {v.topRows(n), v.bottomRows(m)};
}

Eigen::MatrixXd FlatMStep(const Eigen::MatrixXd& snapshot_sums,
                          const Eigen::MatrixXd& correspondences,
                          const Eigen::MatrixXd& previous_objects) {
  Eigen::MatrixXd objects = snapshot_sums;
  const Eigen::VectorXd mass = correspondences.colwise().sum().transpose();
  for (Eigen::Index i = 0; i < objects.rows(); ++i) {
    if (mass(i) < 1e-9) {
      objects.row(i) = previous_objects.row(i);
    } else {
      objects.row(i) /= mass(i);
    }
  }
  return objects;
}

}  // namespace fleetmap::object_learning
