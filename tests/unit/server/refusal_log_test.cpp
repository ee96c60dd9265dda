#include "server/refusal_log.hpp"

#include <gtest/gtest.h>

namespace fleetmap::server {
namespace {

using std::chrono::seconds;

TEST(RefusalLogTest, CountsEveryRefusalPerRobotAndReason) {
  RefusalLog log("test");
  const auto t0 = std::chrono::steady_clock::time_point(seconds(100));
  for (int i = 0; i < 500; ++i) log.Refuse("gamma", fusion::Refusal::kTileQuota, "same", t0);
  log.Refuse("gamma", fusion::Refusal::kNotOwner, "x", t0);
  log.Refuse("", fusion::Refusal::kMalformed, "y", t0);
  EXPECT_EQ(log.count("gamma", fusion::Refusal::kTileQuota), 500u);
  EXPECT_EQ(log.count("gamma", fusion::Refusal::kNotOwner), 1u);
  EXPECT_EQ(log.count("", fusion::Refusal::kMalformed), 1u);
  EXPECT_EQ(log.total(), 502u);
  EXPECT_EQ(log.counts().at("(unnamed)").at(fusion::Refusal::kMalformed), 1u);
}

TEST(RefusalLogTest, AFloodOfRobotIdsIsCountedInBoundedMemory) {
  RefusalLog log("test");
  const auto t0 = std::chrono::steady_clock::time_point(seconds(100));
  for (int i = 0; i < 10000; ++i) {
    std::string robot = "r";  // (not "r" + ...: GCC 12 warns a false -Wrestrict on it)
    robot += std::to_string(i);
    log.Refuse(robot, fusion::Refusal::kUnclaimed, "held too long", t0);
  }
  EXPECT_EQ(log.total(), 10000u);
  EXPECT_LE(log.counts().size(), 4097u);
  EXPECT_GT(log.count("(others)", fusion::Refusal::kUnclaimed), 0u);
}

TEST(RefusalLogTest, ReasonsHaveNames) {
  EXPECT_STREQ(RefusalName(fusion::Refusal::kStampOutOfWindow), "stamp out of window");
  EXPECT_STREQ(RefusalName(fusion::Refusal::kNotOwner), "not the owner");
}

TEST(RefusalLogTest, TwoThousandIdsOfOneParticipantLogNoMoreThanOneId) {
  RefusalLog log("test");
  const auto t0 = std::chrono::steady_clock::time_point(seconds(100));
  for (int i = 0; i < 2000; ++i) {
    std::string robot = "r";
    robot += std::to_string(i);
    // Each id's message differs (it names the id), as the server's do.
    log.RefuseFrom("0102030405060708090a0b0c", robot, fusion::Refusal::kMemoryBudget,
                   robot + " refused", t0);
  }
  EXPECT_EQ(log.lines_logged(), RefusalLog::kLinesPerPeriod);
  EXPECT_EQ(log.count("r1999", fusion::Refusal::kMemoryBudget), 1u);  // still counted per robot
  // The next period sums up what was left out in one line.
  log.RefuseFrom("0102030405060708090a0b0c", "r0", fusion::Refusal::kMemoryBudget, "again",
                 t0 + seconds(11));
  EXPECT_EQ(log.lines_logged(), RefusalLog::kLinesPerPeriod + 2);
  // Per robot (no participant known), each id has its own lines.
  RefusalLog per_robot("test");
  for (int i = 0; i < 100; ++i) {
    std::string robot = "r";
    robot += std::to_string(i);
    per_robot.Refuse(robot, fusion::Refusal::kMemoryBudget, "refused", t0);
  }
  EXPECT_EQ(per_robot.lines_logged(), 100u);
}

}  // namespace
}  // namespace fleetmap::server
