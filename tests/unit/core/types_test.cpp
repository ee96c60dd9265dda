#include "common/core/types.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace fleetmap {
namespace {

TEST(Pose2Test, TransformRoundTrip) {
  const Pose2 pose{1.5, -2.0, 0.75};
  const Pose2 back = Pose2::FromTransform(pose.ToTransform());
  EXPECT_NEAR(back.x, pose.x, 1e-12);
  EXPECT_NEAR(back.y, pose.y, 1e-12);
  EXPECT_NEAR(back.yaw, pose.yaw, 1e-12);
}

TEST(Pose2Test, TransformRotatesThenTranslates) {
  const Transform2 fleet_from_map = Pose2{10.0, 0.0, std::numbers::pi / 2}.ToTransform();
  const Point2 in_fleet = fleet_from_map * Point2(1.0, 0.0);
  EXPECT_NEAR(in_fleet.x(), 10.0, 1e-12);
  EXPECT_NEAR(in_fleet.y(), 1.0, 1e-12);
}

TEST(NormalizeAngleTest, WrapsIntoHalfOpenRange) {
  EXPECT_NEAR(NormalizeAngle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-0.5), -0.5, 1e-12);
}

}  // namespace
}  // namespace fleetmap
