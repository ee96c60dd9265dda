#include "common/fusion/map_frame_robots.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::fusion {
namespace {

// One wall from (1, 1) to (4, 1) in the robot's map frame, in its tile (0, 0) of 10 m.
vector_map::VectorMap Wall(double x0 = 1.0, double x1 = 4.0) {
  vector_map::VectorMap map;
  map.resolution = 0.05;
  map.epsilon = 0.07;
  map.obstacles.push_back(vector_map::Polyline{{Point2(x0, 1.0), Point2(x1, 1.0)}, false, 0.02});
  return map;
}

const RobotId kRobot{"beta"};
constexpr double kTileSize = 10.0;

TEST(MapFrameRobotsTest, KeepsTilesOfAnUnplacedRobotWithoutContributing) {
  MapFrameRobots robots(kTileSize);
  EXPECT_TRUE(robots.UpdateTile(kRobot, TileId{0, 0}, Wall(), Timestamp{}).empty());
  EXPECT_TRUE(robots.Knows(kRobot));
  EXPECT_FALSE(robots.placement(kRobot).has_value());
  EXPECT_FALSE(robots.Contribution(kRobot, TileId{0, 0}).has_value());
  EXPECT_EQ(robots.MapOf(kRobot).obstacles.size(), 1u);
  EXPECT_EQ(robots.changes(kRobot), 1u);
}

TEST(MapFrameRobotsTest, PlacementCarriesTheGeometryIntoTheFleetTilesItReaches) {
  MapFrameRobots robots(kTileSize);
  robots.UpdateTile(kRobot, TileId{0, 0}, Wall(), Timestamp{});
  // A quarter turn and a move: the wall runs from (19, 21) to (19, 24) in the fleet frame.
  const std::set<TileId> changed = robots.Place(kRobot, Pose2{20.0, 20.0, M_PI / 2});
  EXPECT_EQ(changed, (std::set<TileId>{{1, 2}}));
  const auto contribution = robots.Contribution(kRobot, TileId{1, 2});
  ASSERT_TRUE(contribution.has_value());
  ASSERT_EQ(contribution->map.obstacles.size(), 1u);
  const auto& points = contribution->map.obstacles[0].points;
  EXPECT_NEAR(points[0].x(), 19.0, 1e-9);
  EXPECT_NEAR(points[0].y(), 21.0, 1e-9);
  EXPECT_NEAR(points[1].x(), 19.0, 1e-9);
  EXPECT_NEAR(points[1].y(), 24.0, 1e-9);
  EXPECT_DOUBLE_EQ(contribution->map.obstacles[0].half_width, 0.02);
  EXPECT_EQ(contribution->map.frame_id, "fleet");
  EXPECT_FALSE(contribution->map.lattice.enabled());
}

TEST(MapFrameRobotsTest, ARevisionMovesTheContributionInsteadOfAddingOne) {
  MapFrameRobots robots(kTileSize);
  robots.UpdateTile(kRobot, TileId{0, 0}, Wall(), Timestamp{});
  robots.Place(kRobot, Pose2{0.0, 0.0, 0.0});
  ASSERT_TRUE(robots.Contribution(kRobot, TileId{0, 0}).has_value());
  // Revised 30 m east: the old tile loses the robot, the new one gains it, once.
  const std::set<TileId> changed = robots.Place(kRobot, Pose2{30.0, 0.0, 0.0});
  EXPECT_EQ(changed, (std::set<TileId>{{0, 0}, {3, 0}}));
  EXPECT_FALSE(robots.Contribution(kRobot, TileId{0, 0}).has_value());
  const auto moved = robots.Contribution(kRobot, TileId{3, 0});
  ASSERT_TRUE(moved.has_value());
  EXPECT_EQ(moved->map.obstacles.size(), 1u);
}

TEST(MapFrameRobotsTest, AFleetTileGathersEveryOwnTileThatReachesIt) {
  MapFrameRobots robots(kTileSize);
  // Two own tiles whose walls both land in fleet tile (0, 0) after a half-tile move.
  robots.UpdateTile(kRobot, TileId{0, 0}, Wall(6.0, 9.0), Timestamp{} + std::chrono::seconds(1));
  vector_map::VectorMap east = Wall(11.0, 13.0);
  robots.UpdateTile(kRobot, TileId{1, 0}, east, Timestamp{} + std::chrono::seconds(2));
  robots.Place(kRobot, Pose2{-5.0, 0.0, 0.0});
  const auto tile = robots.Contribution(kRobot, TileId{0, 0});
  ASSERT_TRUE(tile.has_value());
  EXPECT_EQ(tile->map.obstacles.size(), 2u);
  EXPECT_EQ(tile->stamp, Timestamp{} + std::chrono::seconds(2));
  // A later revision of one own tile reaches only the fleet tiles it touches, before and after.
  EXPECT_EQ(robots.UpdateTile(kRobot, TileId{1, 0}, Wall(11.0, 17.0), Timestamp{}),
            (std::set<TileId>{{0, 0}, {1, 0}}));
  EXPECT_EQ(robots.RemoveTile(kRobot, TileId{1, 0}), (std::set<TileId>{{0, 0}, {1, 0}}));
  EXPECT_FALSE(robots.Contribution(kRobot, TileId{1, 0}).has_value());
  EXPECT_EQ(robots.Contribution(kRobot, TileId{0, 0})->map.obstacles.size(), 1u);
}

TEST(MapFrameRobotsTest, ForgettingARobotNamesEveryTileItContributedTo) {
  MapFrameRobots robots(kTileSize);
  robots.UpdateTile(kRobot, TileId{0, 0}, Wall(), Timestamp{});
  robots.Place(kRobot, Pose2{15.0, 0.0, 0.0});
  EXPECT_EQ(robots.Forget(kRobot), (std::set<TileId>{{1, 0}}));
  EXPECT_FALSE(robots.Knows(kRobot));
}

}  // namespace
}  // namespace fleetmap::fusion
