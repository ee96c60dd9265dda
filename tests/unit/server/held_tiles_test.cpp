#include "server/held_tiles.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

namespace fleetmap::server {
namespace {

using std::chrono::seconds;
using SteadyTime = std::chrono::steady_clock::time_point;

const SteadyTime kStart{seconds(100)};

transport::TileEvent Tile(const std::string& robot, int x, int vertices = 2) {
  transport::TileEvent event;
  event.tile.robot_id = RobotId{robot};
  event.tile.tile = TileId{x, 0};
  vector_map::Polyline wall;
  for (int i = 0; i < vertices; ++i) wall.points.push_back({0.1 * i, 1.0});
  event.tile.map.obstacles.push_back(wall);
  return event;
}

HeldTiles::Limits SmallLimits() {
  HeldTiles::Limits limits;
  limits.max_robots = 2;
  limits.max_tiles_per_robot = 3;
  limits.max_tiles_per_participant = 4;
  limits.max_bytes = uint64_t{1} << 20;
  limits.wait = std::chrono::milliseconds(10'000);
  return limits;
}

std::vector<transport::TileEvent> ReleaseClaimed(HeldTiles& held, const std::string& owned,
                                                 SteadyTime now, int* expired = nullptr) {
  return held.Release(
      now, [&](const RobotId& robot) { return robot.value == owned; },
      [&](const RobotId&, const TileId&) {
        if (expired != nullptr) ++*expired;
      });
}

TEST(HeldTilesTest, ANewerRevisionOfAHeldTileReplacesItAndCostsNothingMore) {
  HeldTiles held(SmallLimits());
  EXPECT_FALSE(held.Hold(Tile("alpha", 0), "p1", kStart).has_value());
  const uint64_t one = held.bytes();
  auto newer = Tile("alpha", 0);
  newer.tile.revision = 2;
  EXPECT_FALSE(held.Hold(std::move(newer), "p1", kStart).has_value());
  EXPECT_EQ(held.tiles(), 1u);
  EXPECT_EQ(held.bytes(), one);
  const auto released = ReleaseClaimed(held, "alpha", kStart);
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].tile.revision, 2u);
  EXPECT_EQ(held.tiles(), 0u);
  EXPECT_EQ(held.bytes(), 0u);
}

TEST(HeldTilesTest, IdsTilesPerIdAndTilesPerParticipantAreBounded) {
  HeldTiles held(SmallLimits());
  for (int x = 0; x < 3; ++x) EXPECT_FALSE(held.Hold(Tile("a", x), "p1", kStart).has_value());
  auto refused = held.Hold(Tile("a", 3), "p1", kStart);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->reason, fusion::Refusal::kTileQuota);
  EXPECT_NE(refused->detail.find("a robot may hold 3"), std::string::npos) << refused->detail;
  // The participant's fourth tile, under another id: its last.
  EXPECT_FALSE(held.Hold(Tile("b", 0), "p1", kStart).has_value());
  refused = held.Hold(Tile("b", 1), "p1", kStart);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->reason, fusion::Refusal::kTileQuota);
  EXPECT_NE(refused->detail.find("participant p1"), std::string::npos) << refused->detail;
  // A third id, from anyone: too many ids wait already.
  refused = held.Hold(Tile("c", 0), "p2", kStart);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->reason, fusion::Refusal::kUnclaimed);
  // Another participant's tile of a waiting id still fits.
  EXPECT_FALSE(held.Hold(Tile("b", 1), "p2", kStart).has_value());
}

TEST(HeldTilesTest, HeldGeometryIsChargedAgainstTheMemoryBound) {
  HeldTiles::Limits limits = SmallLimits();
  limits.max_bytes = 2 * HeldBytes(Tile("a", 0, 1000));
  HeldTiles held(limits);
  EXPECT_FALSE(held.Hold(Tile("a", 0, 1000), "p1", kStart).has_value());
  EXPECT_FALSE(held.Hold(Tile("a", 1, 1000), "p1", kStart).has_value());
  const auto refused = held.Hold(Tile("a", 2, 1000), "p1", kStart);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->reason, fusion::Refusal::kMemoryBudget);
  EXPECT_EQ(held.bytes(), limits.max_bytes);
  EXPECT_GT(HeldBytes(Tile("a", 0, 1000)), 40'000u);
}

TEST(HeldTilesTest, ClaimedIdsAreReleasedAndTheOthersExpireAfterTheWait) {
  HeldTiles held(SmallLimits());
  held.Hold(Tile("alpha", 0), "p1", kStart);
  held.Hold(Tile("alpha", 1), "p1", kStart);
  held.Hold(Tile("ghost", 0), "p2", kStart);
  int expired = 0;
  // Neither claimed nor old: nothing happens.
  EXPECT_TRUE(ReleaseClaimed(held, "nobody", kStart + seconds(5), &expired).empty());
  EXPECT_EQ(expired, 0);
  EXPECT_EQ(held.tiles(), 3u);
  EXPECT_EQ(ReleaseClaimed(held, "alpha", kStart + seconds(6), &expired).size(), 2u);
  EXPECT_EQ(expired, 0);
  EXPECT_TRUE(ReleaseClaimed(held, "alpha", kStart + seconds(11), &expired).empty());
  EXPECT_EQ(expired, 1);
  EXPECT_EQ(held.tiles(), 0u);
  EXPECT_EQ(held.bytes(), 0u);
  // Room again for the participant and the ids.
  EXPECT_FALSE(held.Hold(Tile("x", 0), "p2", kStart).has_value());
  EXPECT_FALSE(held.Hold(Tile("y", 0), "p2", kStart).has_value());
}

}  // namespace
}  // namespace fleetmap::server
