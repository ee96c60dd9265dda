// A shard's server (docs/shards.md): what it reports of tiles outside its region, and the
// aggregator's join of the shards' grids.
#include <gtest/gtest.h>

#include "server/map_aggregator.hpp"
#include "server/shard_tile_scope.hpp"

namespace fleetmap::server {
namespace {

using std::chrono::seconds;

ShardPlan WestAndEast() {
  return ShardPlan::Create({ShardRegion{"west", 0, 0, 30, 60}, ShardRegion{"east", 30, 0, 60, 60}})
      .value();
}

// A grid of the fleet frame whose origin is cell (x, y) of the 0.5 m lattice.
grid::OccupancyGrid Part(int x, int y, int width, int height, int8_t fill) {
  return grid::OccupancyGrid(width, height, 0.5, Pose2{x * 0.5, y * 0.5, 0.0}, fill);
}

TEST(ShardGridsTest, JoinsTheShardsGridsIntoTheSmallestGridHoldingThem) {
  ShardGrids grids(WestAndEast());
  ASSERT_TRUE(grids.Update("west", Part(0, 0, 60, 40, grid::kFreeValue)).ok());
  EXPECT_EQ(grids.Missing(), std::vector<std::string>{"east"});
  ASSERT_TRUE(grids.Update("east", Part(60, 20, 20, 40, grid::kOccupiedValue)).ok());
  EXPECT_TRUE(grids.Missing().empty());
  StatusOr<grid::OccupancyGrid> joined = grids.Joined(0);
  ASSERT_TRUE(joined.ok()) << joined.status();
  EXPECT_EQ(joined->width(), 80);
  EXPECT_EQ(joined->height(), 60);
  EXPECT_EQ(joined->origin().x, 0.0);
  EXPECT_EQ(joined->at(10, 10), grid::kFreeValue);
  EXPECT_EQ(joined->at(70, 50), grid::kOccupiedValue);
  EXPECT_EQ(joined->at(10, 50), grid::kUnknownValue);  // no shard's grid there
  EXPECT_EQ(joined->at(70, 5), grid::kUnknownValue);
}

TEST(ShardGridsTest, RefusesAShardOutsideThePlanAGridThatDoesNotFitAndTooManyCells) {
  ShardGrids grids(WestAndEast());
  EXPECT_FALSE(grids.Update("north", Part(0, 0, 4, 4, 0)).ok());
  ASSERT_TRUE(grids.Update("west", Part(0, 0, 60, 40, 0)).ok());
  ASSERT_TRUE(grids.Update("east", grid::OccupancyGrid(4, 4, 0.1, Pose2{30, 0, 0})).ok());
  StatusOr<grid::OccupancyGrid> joined = grids.Joined(0);
  ASSERT_FALSE(joined.ok());
  EXPECT_NE(joined.status().message().find("shard east's grid has cells of 0.1 m"),
            std::string::npos)
      << joined.status();
  ASSERT_TRUE(grids.Update("east", Part(60, 0, 20, 40, 0)).ok());
  joined = grids.Joined(1000);
  ASSERT_FALSE(joined.ok());
  EXPECT_EQ(joined.status().code(), StatusCode::kResourceExhausted);
  EXPECT_TRUE(grids.Joined(80 * 40).ok());
}

TEST(ShardTileScopeTest, ReportsATileOnNoRegionOnceAMinutePerRobot) {
  ShardTileScope west(ShardAssignment{WestAndEast(), "west"}, 10.0);
  EXPECT_EQ(west.own_tiles(), (TileBox{0, 0, 2, 5}));
  EXPECT_TRUE(west.Owns(TileId{2, 5}));
  const auto start = std::chrono::steady_clock::time_point(std::chrono::hours(1));
  // The other shard's tile (a writer that does not filter sent it): dropped, never reported.
  EXPECT_FALSE(west.NoteOutside(RobotId{"alpha"}, TileId{3, 0}, start).on_no_shard);
  const ShardTileScope::Outside first = west.NoteOutside(RobotId{"alpha"}, TileId{7, 0}, start);
  EXPECT_TRUE(first.on_no_shard);
  EXPECT_TRUE(first.report_now);
  EXPECT_FALSE(west.NoteOutside(RobotId{"alpha"}, TileId{8, 0}, start + seconds(59)).report_now);
  EXPECT_TRUE(west.NoteOutside(RobotId{"beta"}, TileId{8, 0}, start + seconds(59)).report_now);
  EXPECT_TRUE(west.NoteOutside(RobotId{"alpha"}, TileId{8, 0}, start + seconds(60)).report_now);
  EXPECT_EQ(west.orphan_tiles(), 4u);
  EXPECT_EQ(west.other_shards_tiles(), 1u);
  // Its filter: its own tiles, and the other shard's to tell tiles on no region.
  const transport::TileRegionSelection selection = west.Selection();
  EXPECT_EQ(selection.own, west.own_tiles());
  EXPECT_EQ(selection.others, std::vector<TileBox>{(TileBox{3, 0, 5, 5})});
}

}  // namespace
}  // namespace fleetmap::server
