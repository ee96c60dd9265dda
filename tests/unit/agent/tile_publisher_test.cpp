#include "robot_agent/tile_publisher.hpp"

#include <gtest/gtest.h>

#include "common/process/subprocess.hpp"

namespace fleetmap::agent {
namespace {

using std::chrono::seconds;
using std::chrono::steady_clock;

std::unique_ptr<transport::Participant> LoopbackParticipant() {
  transport::ParticipantOptions options;
  options.domain_id = process::RandomDomainId();
  options.localhost_only = true;
  auto participant = transport::Participant::Create(options);
  EXPECT_TRUE(participant.ok()) << participant.status();
  return participant.ok() ? std::move(participant).value() : nullptr;
}

// 30 x 20 m of free space with a wall every 2 m: six 10 m tiles, all with content.
grid::OccupancyGrid Rooms() {
  grid::OccupancyGrid grid(600, 400, 0.05, Pose2{}, grid::kFreeValue);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (x % 40 == 0 || y % 40 == 0) grid.at(x, y) = grid::kOccupiedValue;
    }
  }
  return grid;
}

TEST(TilePublisherTest, PublishesOnlyTheTilesThatChanged) {
  auto participant = LoopbackParticipant();
  ASSERT_NE(participant, nullptr);
  auto publisher = TilePublisher::Create(*participant, RobotId{"alpha"}, Pose2{}, {});
  ASSERT_TRUE(publisher.ok()) << publisher.status();
  grid::OccupancyGrid grid = Rooms();
  ASSERT_TRUE((*publisher)->Update(grid).ok());
  EXPECT_EQ((*publisher)->pending_tiles(), 6u);
  ASSERT_TRUE((*publisher)->Flush(steady_clock::now()).ok());
  EXPECT_EQ((*publisher)->tiles_published(), 6u);

  // The same grid again: nothing to send.
  ASSERT_TRUE((*publisher)->Update(grid).ok());
  EXPECT_EQ((*publisher)->pending_tiles(), 0u);

  // A new obstacle in the middle of tile (1, 0), far from its borders: only that tile.
  for (int x = 295; x < 305; ++x) grid.at(x, 100) = grid::kOccupiedValue;
  ASSERT_TRUE((*publisher)->Update(grid).ok());
  EXPECT_EQ((*publisher)->pending_tiles(), 1u);
  ASSERT_TRUE((*publisher)->Flush(steady_clock::now()).ok());
  EXPECT_EQ((*publisher)->tiles_published(), 7u);

  // A change right at the border between tiles (0, 0) and (1, 0) touches both.
  grid.at(199, 110) = grid::kOccupiedValue;
  ASSERT_TRUE((*publisher)->Update(grid).ok());
  EXPECT_EQ((*publisher)->pending_tiles(), 2u);
}

TEST(TilePublisherTest, BandwidthBudgetDefersTilesAndCoarsensEpsilon) {
  auto participant = LoopbackParticipant();
  ASSERT_NE(participant, nullptr);
  TilePublisherOptions options;
  // 50 bytes per second, 100 banked at most: less than any tile here (about 150 bytes each).
  options.max_kbps = 0.4;
  auto publisher = TilePublisher::Create(*participant, RobotId{"alpha"}, Pose2{}, options);
  ASSERT_TRUE(publisher.ok()) << publisher.status();
  ASSERT_TRUE((*publisher)->Update(Rooms()).ok());

  const auto start = steady_clock::now();
  ASSERT_TRUE((*publisher)->Flush(start).ok());
  const uint64_t first_second = (*publisher)->bytes_published();
  EXPECT_GT((*publisher)->pending_tiles(), 0u);
  // More than 5 s of budget waiting: the next re-vectorizations are coarser.
  EXPECT_GT((*publisher)->current_epsilon_factor(), 1.0);

  EXPECT_LE((*publisher)->tiles_published(), 1u);
  // Time passes (the publisher is told the time; no real waiting): the backlog drains at the
  // budget's pace. Every tile is larger than the bank, so at most one goes per refill, and only
  // once the bank is full again.
  uint64_t previous_tiles = (*publisher)->tiles_published();
  int flushes_with_a_tile = 0;
  int s = 1;
  for (; s <= 3600 && (*publisher)->pending_tiles() > 0; ++s) {
    ASSERT_TRUE((*publisher)->Flush(start + seconds(s)).ok());
    const uint64_t sent = (*publisher)->tiles_published() - previous_tiles;
    previous_tiles = (*publisher)->tiles_published();
    EXPECT_LE(sent, 1u) << "second " << s;
    flushes_with_a_tile += sent > 0 ? 1 : 0;
  }
  // Draining took at least as long as the bytes need at 50 B/s, less the 100-byte bank.
  EXPECT_GE(50.0 * s + 100.0, static_cast<double>((*publisher)->bytes_published() - first_second));
  EXPECT_GT(flushes_with_a_tile, 1);
  EXPECT_EQ((*publisher)->pending_tiles(), 0u);
  EXPECT_EQ((*publisher)->tiles_published(), 6u);
  EXPECT_EQ((*publisher)->current_epsilon_factor(), 1.0);
}

TEST(TilePublisherOptionsTest, RejectsBadValues) {
  TilePublisherOptions options;
  options.tile_size = 0.0;
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.max_kbps = -1.0;
  EXPECT_NE(options.Validate().message().find("--max-kbps"), std::string::npos);
  options = {};
  options.epsilon = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::agent
