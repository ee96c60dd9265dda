#include "common/registration/placement_groups.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::registration {
namespace {

// Where `point` of `member`'s map lands in the group root's frame.
Point2 InRoot(const PlacementGroup& group, const RobotId& member, const Point2& point) {
  return group.root_from_member.at(member).ToTransform() * point;
}

TEST(PlacementGroupsTest, ARobotWithoutLinksIsAGroupOfOne) {
  const PlacementGroup group = GroupOf(RobotId{"beta"}, {}, {});
  EXPECT_EQ(group.root, RobotId{"beta"});
  EXPECT_TRUE(group.alone());
  EXPECT_EQ(group.root_from_member.at(RobotId{"beta"}), Pose2{});
}

TEST(PlacementGroupsTest, AChainOfLinksIsOneGroupWithTheSameRootAndFramesFromEveryMember) {
  // gamma's map sits 2 m east of beta's origin in beta's frame; delta's sits in gamma's turned a
  // quarter. The links point either way.
  const std::vector<RobotLink> links = {
      {RobotId{"gamma"}, RobotId{"beta"}, Pose2{2.0, 0.0, 0.0}},
      {RobotId{"gamma"}, RobotId{"delta"}, Pose2{0.0, 1.0, M_PI / 2}},  // delta_from_gamma
  };
  const Point2 in_delta(1.0, 0.0);
  // delta_from_gamma takes gamma's (x, y) to (-y, x + 1); so gamma's point is delta's inverse.
  const Point2 in_gamma = Pose2{0.0, 1.0, M_PI / 2}.ToTransform().inverse() * in_delta;
  for (const char* start : {"beta", "gamma", "delta"}) {
    const PlacementGroup group = GroupOf(RobotId{start}, links, {});
    EXPECT_EQ(group.root, RobotId{"beta"}) << start;
    ASSERT_EQ(group.root_from_member.size(), 3u) << start;
    EXPECT_FALSE(group.alone());
    // The same point of delta's map lands where gamma's link says, in beta's frame.
    const Point2 via_delta = InRoot(group, RobotId{"delta"}, in_delta);
    const Point2 via_gamma = InRoot(group, RobotId{"gamma"}, in_gamma);
    EXPECT_NEAR(via_delta.x(), via_gamma.x(), 1e-9) << start;
    EXPECT_NEAR(via_delta.y(), via_gamma.y(), 1e-9) << start;
    EXPECT_NEAR(via_gamma.x(), in_gamma.x() + 2.0, 1e-9) << start;
    EXPECT_NEAR(group.root_from_member.at(RobotId{"beta"}).x, 0.0, 1e-12) << start;
  }
}

TEST(PlacementGroupsTest, PlacedRobotsAreLeftOutAndSplitTheGroup) {
  const std::vector<RobotLink> links = {
      {RobotId{"beta"}, RobotId{"alpha"}, Pose2{1.0, 0.0, 0.0}},
      {RobotId{"gamma"}, RobotId{"alpha"}, Pose2{0.0, 1.0, 0.0}},
  };
  const PlacementGroup group = GroupOf(RobotId{"beta"}, links, {RobotId{"alpha"}});
  EXPECT_EQ(group.root, RobotId{"beta"});
  EXPECT_TRUE(group.alone());
}

}  // namespace
}  // namespace fleetmap::registration
