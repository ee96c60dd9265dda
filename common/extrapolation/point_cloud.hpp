#pragma once

// 3D points for the entity detectors: map frame, metres, z up with the robot's floor at z = 0.

#include <vector>

#include <Eigen/Core>

namespace fleetmap::extrapolation {

using Point3 = Eigen::Vector3d;
using Vector3 = Eigen::Vector3d;
using PointCloud = std::vector<Point3>;

}  // namespace fleetmap::extrapolation
