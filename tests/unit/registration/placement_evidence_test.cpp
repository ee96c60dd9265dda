#include "common/registration/placement_evidence.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fleetmap::registration {
namespace {

using ::testing::HasSubstr;

const RobotId kRobot{"beta"};
const RegistrationKey kOnFleet{kRobot, {}};
const RegistrationKey kOnGamma{kRobot, RobotId{"gamma"}};
const RegistrationKey kGroupOnFleet{kRobot, {}, /*as_group=*/true};

PlacementEvidence::Vote At(double x, double y, double yaw, bool at_bar = true) {
  PlacementEvidence::Vote vote;
  vote.target_from_map = Pose2{x, y, yaw};
  vote.map_centre = Point2(5.0, 5.0);
  vote.at_bar = at_bar;
  vote.confidence = at_bar ? 0.97 : 0.4;
  vote.why_not = at_bar ? "" : "too little shared structure";
  return vote;
}

TEST(PlacementEvidenceTest, OnePlacementAtTheBarWaitsForASecondThatFindsTheSame) {
  PlacementEvidence evidence({});
  const auto first = evidence.Observe(kOnFleet, At(10.0, 2.0, 0.5));
  EXPECT_FALSE(first.place);
  EXPECT_EQ(first.streak, 1);
  EXPECT_THAT(first.why, HasSubstr("waiting for 1 more registration"));
  EXPECT_TRUE(evidence.Pending(kOnFleet));
  // The grown map lands 5 cm away: the same placement.
  const auto second = evidence.Observe(kOnFleet, At(10.05, 2.0, 0.5));
  EXPECT_TRUE(second.place);
  EXPECT_EQ(second.streak, 2);
  EXPECT_TRUE(second.why.empty());
  EXPECT_FALSE(evidence.Pending(kOnFleet));
}

TEST(PlacementEvidenceTest, ARepeatedRoomThatMovesTheBestPlacementStartsTheCountAgain) {
  PlacementEvidence evidence({});
  ASSERT_FALSE(evidence.Observe(kOnFleet, At(10.0, 2.0, 0.0)).place);
  // The next room along the corridor, 6 m east, now wins.
  const auto moved = evidence.Observe(kOnFleet, At(16.0, 2.0, 0.0));
  EXPECT_FALSE(moved.place);
  EXPECT_EQ(moved.streak, 1);
  EXPECT_THAT(moved.why, HasSubstr("the best placement moved"));
  // Turned by 2 degrees about the map centre is another placement too.
  EXPECT_FALSE(evidence.Observe(kOnFleet, At(16.0, 2.0, 0.035)).place);
  EXPECT_TRUE(evidence.Observe(kOnFleet, At(16.0, 2.0, 0.035)).place);
}

TEST(PlacementEvidenceTest, ARegistrationBelowTheBarResetsTheCountAndSaysWhy) {
  PlacementEvidence evidence({});
  ASSERT_FALSE(evidence.Observe(kOnFleet, At(10.0, 2.0, 0.0)).place);
  const auto refused = evidence.Observe(kOnFleet, At(10.0, 2.0, 0.0, false));
  EXPECT_FALSE(refused.place);
  EXPECT_EQ(refused.streak, 0);
  EXPECT_EQ(refused.why, "too little shared structure");
  EXPECT_FALSE(evidence.Pending(kOnFleet));
  EXPECT_FALSE(evidence.Observe(kOnFleet, At(10.0, 2.0, 0.0)).place);
}

TEST(PlacementEvidenceTest, TargetsAndGroupMapsCountApartAndOneConfirmationPlacesAtOnce) {
  PlacementEvidence evidence({});
  ASSERT_FALSE(evidence.Observe(kOnFleet, At(10.0, 2.0, 0.0)).place);
  ASSERT_FALSE(evidence.Observe(kOnGamma, At(1.0, 1.0, 0.0)).place);
  EXPECT_TRUE(evidence.Pending(kOnGamma));
  // The group's merged map refused on the fleet map leaves the robot's own count alone.
  ASSERT_FALSE(evidence.Observe(kGroupOnFleet, At(10.0, 2.0, 0.0, false)).place);
  EXPECT_FALSE(evidence.Pending(kGroupOnFleet));
  EXPECT_TRUE(evidence.Pending(kOnFleet));
  evidence.Forget(kRobot);
  EXPECT_FALSE(evidence.Pending(kOnFleet));
  EXPECT_FALSE(evidence.Pending(kOnGamma));

  PlacementEvidence::Options one_shot;
  one_shot.confirmations = 1;
  PlacementEvidence immediate(one_shot);
  EXPECT_TRUE(immediate.Observe(kOnFleet, At(10.0, 2.0, 0.0)).place);
}

}  // namespace
}  // namespace fleetmap::registration
