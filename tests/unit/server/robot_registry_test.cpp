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
  EXPECT_EQ(registry.ClaimRobot("alpha", kAgentWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot("alpha", kAgentOtherWriter), RobotRegistry::Claim::kSame);
  EXPECT_EQ(registry.ClaimRobot("alpha", kPeerWriter), RobotRegistry::Claim::kClash);
  EXPECT_EQ(registry.WhoSpeaks("alpha", kAgentOtherWriter), RobotRegistry::Speaker::kOwner);
  EXPECT_EQ(registry.WhoSpeaks("alpha", kPeerWriter), RobotRegistry::Speaker::kOther);
  EXPECT_EQ(registry.WhoSpeaks("beta", kPeerWriter), RobotRegistry::Speaker::kUnclaimed);
  EXPECT_EQ(registry.OwnerOf("alpha"), "0102030405060708090a0b0c");
}

TEST(RobotRegistryTest, OnlyTheOwnerReleasesAnId) {
  RobotRegistry registry;
  registry.ClaimRobot("alpha", kAgentWriter);
  EXPECT_FALSE(registry.Release("alpha", kPeerWriter));
  EXPECT_EQ(registry.WhoSpeaks("alpha", kPeerWriter), RobotRegistry::Speaker::kOther);
  EXPECT_TRUE(registry.Release("alpha", kAgentWriter));
  // Free again: a restarted agent (a new participant) may take it.
  EXPECT_EQ(registry.ClaimRobot("alpha", kPeerWriter), RobotRegistry::Claim::kNew);
}

TEST(RobotRegistryTest, AParticipantSpeaksForABoundedNumberOfIds) {
  RobotRegistry registry(2);
  EXPECT_EQ(registry.ClaimRobot("a", kPeerWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot("b", kPeerWriter), RobotRegistry::Claim::kNew);
  EXPECT_EQ(registry.ClaimRobot("c", kPeerWriter), RobotRegistry::Claim::kTooMany);
  EXPECT_EQ(registry.ClaimRobot("c", kAgentWriter), RobotRegistry::Claim::kNew);
  registry.Release("a", kPeerWriter);
  EXPECT_EQ(registry.ClaimRobot("d", kPeerWriter), RobotRegistry::Claim::kNew);
}

}  // namespace
}  // namespace fleetmap::server
