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

// A placement that passed the verification at `confidence`, under the bar, on map revision
// `map_changes`.
PlacementEvidence::Vote Verified(double x, double confidence, uint64_t map_changes) {
  PlacementEvidence::Vote vote = At(x, 2.0, 0.0, /*at_bar=*/false);
  vote.verified = true;
  vote.confidence = confidence;
  vote.why_not = "confidence below the placement bar 0.95";
  vote.map_changes = map_changes;
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

PlacementEvidence::Options Sequential() {
  PlacementEvidence::Options options;
  options.sequential_wins = 3;
  options.sequential_confidence = 0.8;
  return options;
}

TEST(PlacementEvidenceTest, AVerifiedPlacementUnderTheBarPlacesWhenItKeepsWinningAsTheMapGrows) {
  PlacementEvidence evidence(Sequential());
  const auto first = evidence.Observe(kOnFleet, Verified(10.0, 0.86, 1));
  EXPECT_FALSE(first.place);
  EXPECT_EQ(first.wins, 1);
  EXPECT_THAT(first.why, HasSubstr("confidence below the placement bar"));
  EXPECT_THAT(first.why, HasSubstr("waiting for 2 more registration(s)"));
  // Registered again on the same map: no new evidence, no win.
  EXPECT_EQ(evidence.Observe(kOnFleet, Verified(10.0, 0.86, 1)).wins, 1);
  EXPECT_FALSE(evidence.Observe(kOnFleet, Verified(10.02, 0.84, 2)).place);
  const auto third = evidence.Observe(kOnFleet, Verified(10.0, 0.90, 3));
  EXPECT_TRUE(third.place);
  EXPECT_EQ(third.wins, 3);
  EXPECT_EQ(third.streak, 0);  // never at the bar
}

TEST(PlacementEvidenceTest, AWinUnderTheFloorOrARefusalOrAnotherPlaceBreaksTheSequence) {
  PlacementEvidence evidence(Sequential());
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 1)).place);
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 2)).place);
  // Verified, but at 0.6: the count starts again, and the robot says why it waits.
  const auto weak = evidence.Observe(kOnFleet, Verified(10.0, 0.6, 3));
  EXPECT_EQ(weak.wins, 0);
  EXPECT_THAT(weak.why, HasSubstr("confidence below"));
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 4)).place);
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 5)).place);
  // A refusal (contradiction, ambiguity: not verified) at any confidence resets too.
  PlacementEvidence::Vote refused = Verified(10.0, 0.9, 6);
  refused.verified = false;
  EXPECT_EQ(evidence.Observe(kOnFleet, refused).wins, 0);
  // The next room along the corridor wins: counting again from 1.
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 7)).place);
  ASSERT_FALSE(evidence.Observe(kOnFleet, Verified(10.0, 0.9, 8)).place);
  const auto moved = evidence.Observe(kOnFleet, Verified(16.0, 0.9, 9));
  EXPECT_EQ(moved.wins, 1);
  EXPECT_THAT(moved.why, HasSubstr("the best placement moved"));
  // A wait under the bar is no confirmation the same map is registered again for.
  EXPECT_FALSE(evidence.Pending(kOnFleet));

  PlacementEvidence bar_only({});  // the default: the bar alone
  for (uint64_t revision = 1; revision <= 10; ++revision) {
    const auto verdict = bar_only.Observe(kOnFleet, Verified(10.0, 0.94, revision));
    EXPECT_FALSE(verdict.place);
    EXPECT_EQ(verdict.wins, 0);
  }
}

}  // namespace
}  // namespace fleetmap::registration
