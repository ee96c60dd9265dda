#include "common/sim/start_poses.hpp"

#include <gtest/gtest.h>

namespace fleetmap::sim {
namespace {

// A 20 x 10 m free room with a 0.1 m wall all around.
grid::OccupancyGrid Room() {
  grid::OccupancyGrid room(400, 200, 0.05, Pose2{}, grid::kFreeValue);
  for (int y = 0; y < room.height(); ++y) {
    for (int x = 0; x < room.width(); ++x) {
      if (x < 2 || y < 2 || x >= room.width() - 2 || y >= room.height() - 2) {
        room.at(x, y) = grid::kOccupiedValue;
      }
    }
  }
  return room;
}

TEST(StartPosesTest, SpreadsRobotsApartOnFreeCellsAwayFromWalls) {
  const grid::OccupancyGrid room = Room();
  const Pose2 first{1.0, 1.0, 0.3};
  const auto starts = SpreadStarts(room, first, 4, 0.5);
  ASSERT_TRUE(starts.ok()) << starts.status();
  ASSERT_EQ(starts->size(), 4u);
  EXPECT_EQ((*starts)[0], first);
  for (size_t i = 1; i < starts->size(); ++i) {
    const Pose2& pose = (*starts)[i];
    // 0.5 m from the nearest wall cell's centre: at most half a cell nearer its face.
    EXPECT_GE(pose.x, 0.55);
    EXPECT_LE(pose.x, 19.45);
    EXPECT_GE(pose.y, 0.55);
    EXPECT_LE(pose.y, 9.45);
    for (size_t j = 0; j < i; ++j) {
      // Farthest-point sampling in a 20 x 10 m room keeps 4 robots metres apart.
      EXPECT_GT(((*starts)[j].translation() - pose.translation()).norm(), 5.0) << i << " " << j;
    }
  }
  // Deterministic.
  EXPECT_EQ(*starts, *SpreadStarts(room, first, 4, 0.5));
}

TEST(StartPosesTest, RefusesNoRobotsAndNoRoom) {
  EXPECT_FALSE(SpreadStarts(Room(), Pose2{}, 0).ok());
  EXPECT_FALSE(SpreadStarts(Room(), Pose2{}, 2, 50.0).ok());
}

}  // namespace
}  // namespace fleetmap::sim
