#pragma once

// The vocabulary of fleetmap: points, poses and rigid transforms in the plane, and time stamps.
// Frames are named in variables (`fleet_from_map`, `map_from_robot`); see docs/frames.md.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>
#include <ostream>

namespace fleetmap {

// Wall-clock time, as DDS and ROS 2 stamp messages (builtin_interfaces/Time: since the Unix epoch).
using Clock = std::chrono::system_clock;
using Timestamp = Clock::time_point;

using Point2 = Eigen::Vector2d;
using Point2f = Eigen::Vector2f;
// A direction or displacement in the plane (a Point2 by another name, for readability).
using Vector2 = Eigen::Vector2d;
using Transform2 = Eigen::Isometry2d;

// A planar pose: position in metres and heading (yaw) in radians, counter-clockwise from +x.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;

  Point2 translation() const { return {x, y}; }
  bool finite() const;
  Transform2 ToTransform() const;
  static Pose2 FromTransform(const Transform2& transform);

  friend bool operator==(const Pose2&, const Pose2&) = default;
};

std::ostream& operator<<(std::ostream& os, const Pose2& pose);

// Wraps an angle into (-pi, pi].
double NormalizeAngle(double radians);

}  // namespace fleetmap
