#include "common/extrapolation/ransac_plane.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace fleetmap::extrapolation {
namespace {

// SplitMix64: a tiny, fully specified generator, so fits are the same on every platform.
class SplitMix {
 public:
  explicit SplitMix(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  int Below(int n) { return static_cast<int>(Next() % static_cast<uint64_t>(n)); }

 private:
  uint64_t state_;
};

Plane Oriented(Vector3 normal, const Point3& on_plane) {
  normal.normalize();
  if (normal.z() < 0.0) normal = -normal;
  return {normal, -normal.dot(on_plane)};
}

bool TiltAllowed(const Plane& plane, const RansacOptions& options) {
  const double tilt = plane.Tilt();
  return tilt >= options.min_tilt && tilt <= options.max_tilt;
}

std::vector<int> Inliers(const PointCloud& points, const Plane& plane, double threshold) {
  std::vector<int> inliers;
  for (size_t i = 0; i < points.size(); ++i) {
    if (std::abs(plane.Distance(points[i])) <= threshold) inliers.push_back(static_cast<int>(i));
  }
  return inliers;
}

}  // namespace

double Plane::Tilt() const { return std::acos(std::clamp(std::abs(normal.z()), 0.0, 1.0)); }

Plane FitPlaneLeastSquares(const PointCloud& points) {
  Point3 mean = Point3::Zero();
  for (const Point3& p : points) mean += p;
  mean /= static_cast<double>(std::max<size_t>(1, points.size()));
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Point3& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  return Oriented(solver.eigenvectors().col(0), mean);
}

std::optional<PlaneFit> FitPlaneRansac(const PointCloud& points, const RansacOptions& options) {
  const int n = static_cast<int>(points.size());
  if (n < 3 || n < options.min_inliers) return std::nullopt;
  SplitMix random(options.seed);
  std::optional<Plane> best;
  size_t best_count = 0;
  const int stride = std::max(1, n / std::max(1, options.max_scored_points));
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const int a = random.Below(n), b = random.Below(n), c = random.Below(n);
    if (a == b || b == c || a == c) continue;
    const Vector3 normal = (points[b] - points[a]).cross(points[c] - points[a]);
    if (normal.norm() < 1e-9) continue;
    const Plane plane = Oriented(normal, points[a]);
    if (!TiltAllowed(plane, options)) continue;
    size_t count = 0;
    for (int i = 0; i < n; i += stride) {
      count += std::abs(plane.Distance(points[i])) <= options.distance_threshold;
    }
    if (count > best_count) {
      best_count = count;
      best = plane;
    }
  }
  if (!best) return std::nullopt;
  PlaneFit fit{*best, Inliers(points, *best, options.distance_threshold)};
  if (fit.inliers.size() < static_cast<size_t>(options.min_inliers)) return std::nullopt;
  // Refit on the inliers (twice: the band moves with the plane), keeping the tilt constraint.
  for (int round = 0; round < 2; ++round) {
    PointCloud inlier_points;
    for (int i : fit.inliers) inlier_points.push_back(points[i]);
    const Plane refined = FitPlaneLeastSquares(inlier_points);
    if (!TiltAllowed(refined, options)) break;
    std::vector<int> inliers = Inliers(points, refined, options.distance_threshold);
    if (inliers.size() < fit.inliers.size()) break;
    fit = {refined, std::move(inliers)};
  }
  return fit;
}

PointCloud WithoutInliers(const PointCloud& points, const std::vector<int>& inliers) {
  std::vector<uint8_t> drop(points.size(), 0);
  for (const int i : inliers) drop[static_cast<size_t>(i)] = 1;
  PointCloud rest;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!drop[i]) rest.push_back(points[i]);
  }
  return rest;
}

}  // namespace fleetmap::extrapolation
