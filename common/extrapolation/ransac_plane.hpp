#pragma once

// RANSAC plane fitting (Fischler and Bolles 1981) with a least-squares refit on the inliers, and
// an optional constraint on the plane's tilt (angle between its normal and +z), so a detector can
// ask for "vertical planes" or "planes about 45 degrees from vertical" only.
//
// Thread-safety: stateless; the random draws come from `seed`, so results are reproducible.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/extrapolation/point_cloud.hpp"

namespace fleetmap::extrapolation {

struct Plane {
  Vector3 normal = Vector3::UnitZ();  // unit, n_z >= 0 (horizontal normals: any sign)
  double offset = 0;                  // n . p + offset = 0 on the plane

  double Distance(const Point3& p) const { return normal.dot(p) + offset; }
  // Angle between the normal and +z, radians in [0, pi/2].
  double Tilt() const;
};

struct RansacOptions {
  double distance_threshold = 0.03;  // metres: inlier band half-width
  int iterations = 300;
  int min_inliers = 50;
  // Accept only hypotheses whose tilt is within [min_tilt, max_tilt] (radians).
  double min_tilt = 0.0;
  double max_tilt = 1.5707963267948966;
  uint32_t seed = 1;
  // Hypotheses are scored on at most this many points (an even stride through the input), so a
  // large cloud costs iterations x this, not iterations x its size; the winner's inliers are then
  // taken from every point. min_inliers is compared with the full count.
  int max_scored_points = 40000;
};

struct PlaneFit {
  Plane plane;
  std::vector<int> inliers;  // indices into the input, ascending
};

// The plane with the most inliers, refitted by least squares (and re-scored), or nothing if no
// hypothesis meets the constraints with min_inliers.
std::optional<PlaneFit> FitPlaneRansac(const PointCloud& points, const RansacOptions& options);

// The points that are not among `inliers` (indices into `points`, as PlaneFit gives them), in
// their order: what a detector searches next after taking one plane out.
PointCloud WithoutInliers(const PointCloud& points, const std::vector<int>& inliers);

// The least-squares plane through `points` (>= 3): the normal is the eigenvector of the smallest
// eigenvalue of their covariance.
Plane FitPlaneLeastSquares(const PointCloud& points);

}  // namespace fleetmap::extrapolation
