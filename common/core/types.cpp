#include "common/core/types.hpp"

#include <cmath>
#include <numbers>

namespace fleetmap {

bool Pose2::finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(yaw); }

Transform2 Pose2::ToTransform() const {
  Transform2 transform = Transform2::Identity();
  transform.translate(Point2(x, y));
  transform.rotate(yaw);
  return transform;
}

Pose2 Pose2::FromTransform(const Transform2& transform) {
  const Eigen::Rotation2Dd rotation(transform.rotation());
  return {transform.translation().x(), transform.translation().y(),
          NormalizeAngle(rotation.angle())};
}

std::ostream& operator<<(std::ostream& os, const Pose2& pose) {
  return os << "(" << pose.x << ", " << pose.y << ", " << pose.yaw << " rad)";
}

double NormalizeAngle(double radians) {
  double wrapped = std::remainder(radians, 2.0 * std::numbers::pi);
  if (wrapped <= -std::numbers::pi) wrapped += 2.0 * std::numbers::pi;
  return wrapped;
}

}  // namespace fleetmap
