#include "common/fusion/robot_trust.hpp"

#include <gtest/gtest.h>

namespace fleetmap::fusion {
namespace {

// At 5 cm, the default 2 m of wall is 40 cells and the cap of 10 m is 200.
constexpr double kResolution = 0.05;
const RobotId kRobot{"delta"};

TileContradiction Counted(int64_t contradicted, int64_t seen) {
  TileContradiction counted;
  counted.contradicted = contradicted;
  counted.established_seen = seen;
  if (contradicted > 0) {
    counted.min_x = 2;
    counted.min_y = 4;
    counted.max_x = 11;
    counted.max_y = 5;
  }
  return counted;
}

TileContradiction Walls(int64_t known, int64_t confirmed) {
  TileContradiction counted;
  counted.walls_known = known;
  counted.walls_confirmed = confirmed;
  return counted;
}

TEST(RobotTrustTest, IsCorroboratedPastBothTheLengthAndTheShareOfConfirmedWalls) {
  RobotTrust trust(QuarantineOptions{}, 10.0, kResolution);
  EXPECT_FALSE(trust.corroborated(kRobot));
  trust.Record(kRobot, {0, 0}, Walls(60, 39));  // 65 % but under 2 m
  EXPECT_FALSE(trust.Corroborate(kRobot));
  trust.Record(kRobot, {1, 0}, Walls(60, 6));  // 45 of 120: 2.25 m but 38 %
  EXPECT_FALSE(trust.Corroborate(kRobot));
  EXPECT_FALSE(trust.corroborated(kRobot));
  trust.Record(kRobot, {1, 0}, Walls(60, 30));  // 69 of 120: 58 %
  EXPECT_TRUE(trust.Corroborate(kRobot));
  EXPECT_TRUE(trust.corroborated(kRobot));
  EXPECT_FALSE(trust.Corroborate(kRobot));  // unchanged
  // Its map moved and disagrees now: it stays corroborated, until its data are forgotten.
  trust.Record(kRobot, {1, 0}, Walls(60, 0));
  EXPECT_FALSE(trust.Corroborate(kRobot));
  EXPECT_TRUE(trust.corroborated(kRobot));
  trust.Forget(kRobot);
  EXPECT_FALSE(trust.corroborated(kRobot));
}

TEST(RobotTrustTest, EntersQuarantineOnlyPastBothTheLengthAndTheShare) {
  RobotTrust trust(QuarantineOptions{}, 10.0, kResolution);
  trust.Record(kRobot, {0, 0}, Counted(39, 100));  // 39 % but under 2 m
  EXPECT_FALSE(trust.Decide(kRobot));
  trust.Record(kRobot, {0, 0}, Counted(60, 1000));  // 3 m but 6 %
  EXPECT_FALSE(trust.Decide(kRobot));
  EXPECT_EQ(trust.standing(kRobot), Standing::kTrusted);
  trust.Record(kRobot, {1, 0}, Counted(40, 100));  // together: 100 of 1100 cells, 9 %
  EXPECT_FALSE(trust.Decide(kRobot));
  trust.Record(kRobot, {2, 0}, Counted(40, 0));  // 140 of 1100: 12.7 %
  EXPECT_TRUE(trust.Decide(kRobot));
  EXPECT_EQ(trust.standing(kRobot), Standing::kQuarantined);
  const TrustReport report = trust.Report(kRobot);
  EXPECT_EQ(report.contradicted_cells, 140);
  EXPECT_NEAR(report.share, 140.0 / 1100.0, 1e-12);
  EXPECT_NE(report.reason.find("7.0 m of walls"), std::string::npos) << report.reason;
  // The area spans the three tiles' boxes, in fleet metres.
  EXPECT_NEAR(report.area_min.x(), 0.10, 1e-9);
  EXPECT_NEAR(report.area_max.x(), 20.60, 1e-9);
  EXPECT_NEAR(report.area_max.y(), 0.30, 1e-9);
}

TEST(RobotTrustTest, ErasingManyWallsIsQuarantinedWhateverItAgreesWithElsewhere) {
  RobotTrust trust(QuarantineOptions{}, 10.0, kResolution);
  trust.Record(kRobot, {0, 0}, Counted(200, 100000));  // 10 m of wall, 0.2 %
  EXPECT_TRUE(trust.Decide(kRobot));
  EXPECT_TRUE(trust.quarantined(kRobot));
}

TEST(RobotTrustTest, LeavesWhenItAgreesAgainWithHysteresis) {
  RobotTrust trust(QuarantineOptions{}, 10.0, kResolution);
  trust.Record(kRobot, {0, 0}, Counted(100, 500));
  ASSERT_TRUE(trust.Decide(kRobot));
  trust.Record(kRobot, {0, 0}, Counted(45, 500));  // 9 %: below entry, above the 4 % exit
  EXPECT_FALSE(trust.Decide(kRobot));
  EXPECT_TRUE(trust.quarantined(kRobot));
  trust.Record(kRobot, {0, 0}, Counted(10, 500));  // relocalized: under 2 m
  EXPECT_TRUE(trust.Decide(kRobot));
  EXPECT_EQ(trust.standing(kRobot), Standing::kTrusted);
  EXPECT_NE(trust.Report(kRobot).reason.find("agrees"), std::string::npos);
}

TEST(RobotTrustTest, AnAdmittedRobotIsNeverQuarantinedAgain) {
  RobotTrust trust(QuarantineOptions{}, 10.0, kResolution);
  trust.Record(kRobot, {0, 0}, Counted(500, 500));
  ASSERT_TRUE(trust.Decide(kRobot));
  EXPECT_TRUE(trust.Admit(kRobot));
  EXPECT_FALSE(trust.Admit(kRobot));
  trust.Record(kRobot, {1, 0}, Counted(500, 500));
  EXPECT_FALSE(trust.Decide(kRobot));
  EXPECT_EQ(trust.standing(kRobot), Standing::kAdmitted);
}

TEST(RobotTrustTest, DisabledNeverQuarantines) {
  QuarantineOptions options;
  options.enabled = false;
  RobotTrust trust(options, 10.0, kResolution);
  trust.Record(kRobot, {0, 0}, Counted(5000, 5000));
  EXPECT_FALSE(trust.Decide(kRobot));
  EXPECT_FALSE(trust.quarantined(kRobot));
}

TEST(QuarantineOptionsTest, RefusesSharesOutOfOrder) {
  QuarantineOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.leave_share = 0.2;  // above enter_share
  EXPECT_FALSE(options.Validate().ok());
  options = QuarantineOptions{};
  options.max_contradicted_m = 1.0;  // below min_contradicted_m
  EXPECT_FALSE(options.Validate().ok());
  options = QuarantineOptions{};
  options.tolerance_m = -1.0;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::fusion
