#include "server/robot_registry.hpp"

#include <gtest/gtest.h>

namespace fleetmap::server {
namespace {

// Writer ids: 24 hex digits of participant, 8 of entity.
const std::string kAgentWriter = "0102030405060708090a0b0c00000103";
const std::string kAgentOtherWriter = "0102030405060708090a0b0c00000203";
const std::string kPeerWriter = "ffffffffffffffffffffffff00000103";

TEST(RobotRegistryTest, TheFirstParticipantOwnsAnIdAndOthersClash) {
  RobotRegistry registry;
  EXPECT_EQ(registry.ClaimRobot(RobotId{"alpha"}, kAgentWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"alpha"}, kAgentOtherWriter), RobotRegistry::Claim::kSame);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"alpha"}, kPeerWriter), RobotRegistry::Claim::kClash);
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"alpha"}, kAgentOtherWriter),
            RobotRegistry::Speaker::kOwner);
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"alpha"}, kPeerWriter), RobotRegistry::Speaker::kOther);
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"beta"}, kPeerWriter), RobotRegistry::Speaker::kUnclaimed);
  EXPECT_EQ(registry.OwnerOf(RobotId{"alpha"}), "0102030405060708090a0b0c");
}

TEST(RobotRegistryTest, OnlyTheOwnerReleasesAnId) {
  RobotRegistry registry;
  registry.ClaimRobot(RobotId{"alpha"}, kAgentWriter);
  EXPECT_FALSE(registry.Release(RobotId{"alpha"}, kPeerWriter));
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"alpha"}, kPeerWriter), RobotRegistry::Speaker::kOther);
  EXPECT_TRUE(registry.Release(RobotId{"alpha"}, kAgentWriter));
  // Free again: a restarted agent (a new participant) may take it.
  EXPECT_EQ(registry.ClaimRobot(RobotId{"alpha"}, kPeerWriter), RobotRegistry::Claim::kNew);
}

TEST(RobotRegistryTest, AParticipantSpeaksForABoundedNumberOfIds) {
  RobotRegistry registry(2);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"a"}, kPeerWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"b"}, kPeerWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"c"}, kPeerWriter), RobotRegistry::Claim::kTooMany);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"c"}, kAgentWriter), RobotRegistry::Claim::kNew);
  // What the full participant sends for a free id need not wait for its status: it would fail.
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"e"}, kPeerWriter), RobotRegistry::Speaker::kOverCap);
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"e"}, kAgentWriter), RobotRegistry::Speaker::kUnclaimed);
  registry.Release(RobotId{"a"}, kPeerWriter);
  EXPECT_EQ(registry.WhoSpeaks(RobotId{"e"}, kPeerWriter), RobotRegistry::Speaker::kUnclaimed);
  EXPECT_EQ(registry.ClaimRobot(RobotId{"d"}, kPeerWriter), RobotRegistry::Claim::kNew);
}

}  // namespace
}  // namespace fleetmap::server
