#include "common/fusion/tile_admission.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fleetmap::fusion {
namespace {

using std::chrono::hours;
using std::chrono::seconds;
using ::testing::HasSubstr;

const Timestamp kNow = Timestamp(hours(24 * 365 * 56));  // 2026
const auto kSteady = std::chrono::steady_clock::time_point(hours(1));

vector_map::VectorTile Tile(const std::string& robot, TileId key = {0, 0}) {
  vector_map::VectorTile tile;
  tile.robot_id = RobotId{robot};
  tile.tile = key;
  tile.stamp = kNow - seconds(1);
  tile.tile_size = 10.0;
  tile.map.epsilon = 0.07;
  tile.map.resolution = 0.05;
  return tile;
}

// The refusal, or a failure naming the admitted stamp.
TileAdmission::Refused RefusalOf(const TileAdmission::Verdict& verdict) {
  const auto* refused = std::get_if<TileAdmission::Refused>(&verdict);
  if (refused == nullptr) {
    ADD_FAILURE() << "admitted";
    return {};
  }
  return *refused;
}

class TileAdmissionTest : public ::testing::Test {
 protected:
  TileAdmissionTest() : admission_(Options(), fusion::FusionOptions()) {}

  static AdmissionOptions Options() {
    AdmissionOptions options;
    options.max_tiles_per_robot = 3;
    options.max_bytes_per_second = 1000.0;
    options.burst_bytes = 5000.0;
    return options;
  }

  TileAdmission::Verdict Admit(const vector_map::VectorTile& tile, size_t bytes = 100,
                               std::chrono::steady_clock::time_point at = kSteady) {
    return admission_.Admit(tile, bytes, kNow, at);
  }

  TileAdmission admission_;
};

TEST_F(TileAdmissionTest, AnHonestTileIsAdmittedWithItsOwnStamp) {
  const auto verdict = Admit(Tile("alpha"));
  ASSERT_TRUE(std::holds_alternative<TileAdmission::Admitted>(verdict));
  EXPECT_EQ(std::get<TileAdmission::Admitted>(verdict).evidence_stamp, kNow - seconds(1));
  EXPECT_EQ(admission_.tiles_held(RobotId{"alpha"}), 1u);
}

TEST_F(TileAdmissionTest, RobotIdsMustBeNameTokensAndNotTheFleet) {
  for (const std::string& bad :
       std::vector<std::string>{"", "fleet", "bad robot", std::string(300, 'a'), "9lives"}) {
    const auto refused = RefusalOf(Admit(Tile(bad)));
    EXPECT_EQ(refused.reason, Refusal::kBadRobotId) << bad;
  }
}

TEST_F(TileAdmissionTest, FarKeysAreRefusedWithTheirDistance) {
  const auto refused = RefusalOf(Admit(Tile("alpha", {INT32_MAX, INT32_MAX})));
  EXPECT_EQ(refused.reason, Refusal::kTileOutOfRange);
  EXPECT_THAT(refused.detail, HasSubstr("from the fleet origin"));
  // 1000 km is a place on Earth: admitted.
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("alpha", {100000, 0}))));
}

TEST_F(TileAdmissionTest, TileSettingsMustMatchTheFleet) {
  auto other_size = Tile("alpha");
  other_size.tile_size = 20.0;
  EXPECT_THAT(RefusalOf(Admit(other_size)).detail, HasSubstr("this fleet's tiles are 10 m"));
  auto huge_epsilon = Tile("alpha");
  huge_epsilon.map.epsilon = 5.0;
  EXPECT_EQ(RefusalOf(Admit(huge_epsilon)).reason, Refusal::kBadTileSettings);
  auto tiny_cells = Tile("alpha");
  tiny_cells.map.resolution = 1e-6;
  EXPECT_EQ(RefusalOf(Admit(tiny_cells)).reason, Refusal::kBadTileSettings);
}

TEST_F(TileAdmissionTest, StampsOutsideTheWindowAreRefused) {
  auto ahead = Tile("alpha");
  ahead.stamp = kNow + hours(24 * 365);
  const auto refused = RefusalOf(Admit(ahead));
  EXPECT_EQ(refused.reason, Refusal::kStampOutOfWindow);
  EXPECT_THAT(refused.detail, HasSubstr("ahead of this server's clock"));
  auto before_epoch = Tile("alpha");
  before_epoch.stamp = Timestamp(-seconds(5));
  EXPECT_EQ(RefusalOf(Admit(before_epoch)).reason, Refusal::kStampOutOfWindow);
}

TEST_F(TileAdmissionTest, ASmallClockLeadIsAdmittedButDatedAtArrival) {
  auto ahead = Tile("alpha");
  ahead.stamp = kNow + seconds(10);
  const auto verdict = Admit(ahead);
  ASSERT_TRUE(std::holds_alternative<TileAdmission::Admitted>(verdict));
  EXPECT_EQ(std::get<TileAdmission::Admitted>(verdict).evidence_stamp, kNow);
}

TEST_F(TileAdmissionTest, ARobotHoldsAtMostItsQuotaOfTilesAndMayUpdateThem) {
  for (int x = 0; x < 3; ++x) {
    ASSERT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("alpha", {x, 0}))));
  }
  EXPECT_EQ(RefusalOf(Admit(Tile("alpha", {3, 0}))).reason, Refusal::kTileQuota);
  // Its own tiles still update, and another robot has its own quota.
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("alpha", {1, 0}))));
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("beta", {3, 0}))));
  // A removed tile frees its place.
  admission_.Forget(RobotId{"alpha"}, {0, 0});
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("alpha", {3, 0}))));
}

TEST_F(TileAdmissionTest, BytesBeyondTheBurstWaitForTheSustainedRate) {
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(Admit(Tile("alpha"), 4000)));
  EXPECT_EQ(RefusalOf(Admit(Tile("alpha"), 4000)).reason, Refusal::kByteQuota);
  // Three seconds at 1000 bytes/s later, 4000 bytes fit again (1000 left + 3000).
  EXPECT_TRUE(std::holds_alternative<TileAdmission::Admitted>(
      Admit(Tile("alpha"), 4000, kSteady + seconds(3))));
}

}  // namespace
}  // namespace fleetmap::fusion
