#include "common/extrapolation/door_space.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/extrapolation/test_maps.hpp"

namespace fleetmap::extrapolation {
namespace {

using testing::Corridor;
using testing::DoorAt;
using testing::Fill;
using testing::kRes;

// The window of the map's lattice within 2.5 m of the door's centre.
CellWindow WindowAroundDoor(const scene::DoorEntity& door) {
  const Point2 c = door.center();
  const int reach = static_cast<int>(std::ceil(2.5 / kRes));
  CellWindow window;
  window.x0 = static_cast<int>(std::floor(c.x() / kRes)) - reach;
  window.y0 = static_cast<int>(std::floor(c.y() / kRes)) - reach;
  window.width = window.height = 2 * reach + 1;
  return window;
}

bool AllowedAt(const DoorSpace& space, const CellWindow& window, const Point2& p) {
  const int x = static_cast<int>(std::floor(p.x() / kRes)) - window.x0;
  const int y = static_cast<int>(std::floor(p.y() / kRes)) - window.y0;
  return space.allowed()[static_cast<size_t>(y) * window.width + x] != 0;
}

// Corridor() ending at x = 6 in a wall the robot saw end-on (its face at x in [6, 6.05)).
grid::OccupancyGrid CorridorWithEndWall() {
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 6.0, 0.0, 10.0, 2.15, grid::kUnknownValue);
  Fill(&map, 6.0, 0.15, 6.05, 2.0, grid::kOccupiedValue);
  return map;
}

TEST(DoorSpaceTest, CorridorsEndWallIsContinuedAsTheEndRoomsSideWall) {
  const scene::DoorEntity door = DoorAt("door_1", 5.0, 5.9, 2.075, false);
  const CellWindow window = WindowAroundDoor(door);
  const DoorSpace walled(CorridorWithEndWall(), door, Vector2(0, 1), window, {});
  EXPECT_TRUE(AllowedAt(walled, window, Point2(5.5, 3.0)));
  EXPECT_FALSE(AllowedAt(walled, window, Point2(6.02, 3.0)));  // on the continued line
  // Without the end wall the room may go on past x = 6: the test can fail.
  const DoorSpace open(Corridor(), door, Vector2(0, 1), window, {});
  EXPECT_TRUE(AllowedAt(open, window, Point2(6.02, 3.0)));
  // The flood stops at the continued wall.
  const std::vector<uint8_t> reached = walled.ReachableFromDoorway(walled.allowed());
  for (int y = 0; y < window.height; ++y) {
    for (int x = 0; x < window.width; ++x) {
      if (reached[static_cast<size_t>(y) * window.width + x]) {
        EXPECT_LT((window.x0 + x + 0.5) * kRes, 6.0);
      }
    }
  }
}

TEST(DoorSpaceTest, UnknownCellsBehindASeenFaceAreWallUpToTheThickness) {
  // A neighbour room at x >= 5.3 whose left wall's face (x in [5.25, 5.3)) the robot saw, with a
  // laser dropout of three cells in it.
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 5.3, 2.15, 8.0, 5.0, grid::kFreeValue);
  Fill(&map, 5.25, 2.15, 5.3, 5.0, grid::kOccupiedValue);
  Fill(&map, 5.25, 3.5, 5.3, 3.65, grid::kUnknownValue);
  const scene::DoorEntity door = DoorAt("door_1", 4.0, 4.9, 2.075, false);
  const CellWindow window = WindowAroundDoor(door);
  DoorSpaceOptions options;
  const DoorSpace space(map, door, Vector2(0, 1), window, options);
  EXPECT_FALSE(AllowedAt(space, window, Point2(5.27, 3.57)));  // the dropout
  EXPECT_FALSE(AllowedAt(space, window, Point2(5.0, 3.0)));    // 0.25 m behind the face
  EXPECT_FALSE(AllowedAt(space, window, Point2(5.0, 3.57)));   // behind the dropout
  EXPECT_TRUE(AllowedAt(space, window, Point2(4.85, 3.0)));    // 0.4 m behind: the room
  EXPECT_FALSE(AllowedAt(space, window, Point2(6.0, 3.0)));    // observed free: another place
  // The doorway is never wall, though the corridor's wall face lies in front of it.
  EXPECT_TRUE(AllowedAt(space, window, Point2(4.45, 2.3)));
  EXPECT_FALSE(AllowedAt(space, window, Point2(3.5, 2.3)));  // the door's wall beside it
}

TEST(DoorSpaceTest, EitherJambAsTheHingeGivesTheSameSpace) {
  const grid::OccupancyGrid map = CorridorWithEndWall();
  const scene::DoorEntity door = DoorAt("door_1", 5.0, 5.9, 2.075, false);
  const scene::DoorEntity swapped = DoorAt("door_1", 5.9, 5.0, 2.075, false);
  const CellWindow window = WindowAroundDoor(door);
  const DoorSpace a(map, door, Vector2(0, 1), window, {});
  const DoorSpace b(map, swapped, Vector2(0, 1), window, {});
  EXPECT_EQ(a.allowed(), b.allowed());
  EXPECT_EQ(a.ReachableFromDoorway(a.allowed()), b.ReachableFromDoorway(b.allowed()));
}

}  // namespace
}  // namespace fleetmap::extrapolation
