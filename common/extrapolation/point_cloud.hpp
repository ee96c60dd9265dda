#pragma once

// 3D points for the entity detectors: map frame, metres, z up with the robot's floor at z = 0.

#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace fleetmap::extrapolation {

using Point3 = Eigen::Vector3d;
using Vector3 = Eigen::Vector3d;
using PointCloud = std::vector<Point3>;

// The value below which `fraction` (in [0, 1]) of `values` lie (nearest rank), 0 for none: the
// detectors read heights and extents robustly with it, ignoring a few stray points.
inline double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const size_t k = static_cast<size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace fleetmap::extrapolation
