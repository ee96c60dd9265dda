#include "common/sim/indoor_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/sim/depth_sensor.hpp"
#include "common/sim/indoor_scene_generator.hpp"
#include "common/sim/people.hpp"

namespace fleetmap::sim {
namespace {

grid::CellState At(const grid::OccupancyGrid& grid, const Point2& p) {
  const auto cell = grid.CellAt(p);
  return cell ? grid.StateAt(cell->x, cell->y) : grid::CellState::kUnknown;
}

TEST(IndoorSceneTest, SameSeedSameSceneOtherSeedOther) {
  const IndoorScene a = GenerateIndoorScene({}, 3), b = GenerateIndoorScene({}, 3);
  const IndoorScene c = GenerateIndoorScene({}, 4);
  ASSERT_EQ(a.doors.size(), b.doors.size());
  for (size_t i = 0; i < a.doors.size(); ++i) EXPECT_EQ(a.doors[i].hinge, b.doors[i].hinge);
  EXPECT_EQ(a.stairs.foot, b.stairs.foot);
  const auto ga = RasterizeGroundFloor(a, 0.05, true), gc = RasterizeGroundFloor(c, 0.05, true);
  ASSERT_TRUE(ga.ok() && gc.ok());
  EXPECT_EQ(*ga, *RasterizeGroundFloor(b, 0.05, true));
  EXPECT_NE(ga->data(), gc->data());
}

TEST(IndoorSceneTest, ClosedDoorsCloseTheRoomsAndTheTruthOpensThem) {
  IndoorSceneOptions options;
  options.closed_door_probability = 1.0;
  const IndoorScene scene = GenerateIndoorScene(options, 8);
  ASSERT_GE(scene.doors.size(), 4u);
  const auto as_set = RasterizeGroundFloor(scene, 0.05, true);
  const auto truth = RasterizeGroundFloor(scene, 0.05, false);
  ASSERT_TRUE(as_set.ok() && truth.ok());
  for (const SceneDoor& door : scene.doors) {
    EXPECT_FALSE(door.open);
    EXPECT_EQ(At(*as_set, door.center()), grid::CellState::kOccupied);
    EXPECT_EQ(At(*truth, door.center()), grid::CellState::kFree);
    // The room behind is free space in the truth.
    EXPECT_EQ(At(*truth, door.center() + 0.5 * door.room_side), grid::CellState::kFree);
    EXPECT_NEAR(door.width(), 0.925, 0.08);
  }
}

TEST(IndoorSceneTest, UpperFloorIsFreeOnlyInTheHallBeyondTheStairs) {
  const IndoorScene scene = GenerateIndoorScene({}, 2);
  const auto upper = RasterizeUpperFloor(scene, 0.05);
  ASSERT_TRUE(upper.ok());
  const Point2 top = scene.stairs.top();
  EXPECT_EQ(At(*upper, top + Vector2(0.3, 0.0)), grid::CellState::kFree);
  EXPECT_EQ(At(*upper, top - Vector2(0.3, 0.0)), grid::CellState::kOccupied);  // the stairwell
  EXPECT_EQ(At(*upper, scene.corridor_min + Vector2(1, 0.5)), grid::CellState::kOccupied);
  EXPECT_NEAR(scene.stairs.height(), 3.0, 0.11);
  EXPECT_NEAR(scene.stairs.rise, 0.17, 0.01);
}

TEST(DepthSensorTest, SeesTheFloorAndAWallAtTheRightDistance) {
  const std::vector<Box3> wall = {{Point2(3.0, 0.0), 0.0, 0.05, 5.0, 0.0, 2.5}};
  // Straight ahead at 1 m height: the wall's face at x = 2.95.
  EXPECT_NEAR(DepthSensor::CastRay(wall, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0)), 2.95,
              1e-9);
  // Straight down: the floor.
  EXPECT_NEAR(DepthSensor::CastRay(wall, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1)), 1.0,
              1e-9);
  const auto sensor = DepthSensor::Create({});
  ASSERT_TRUE(sensor.ok());
  Random random(1);
  const auto points = sensor->Capture(wall, CameraPose{}, &random);
  ASSERT_GT(points.size(), 1000u);
  for (const Eigen::Vector3d& p : points) {
    // Every point is on the floor or on the wall's face, within the noise.
    const bool floor = std::abs(p.z()) < 0.1, face = std::abs(p.x() - 2.95) < 0.1;
    EXPECT_TRUE(floor || face) << p.transpose();
  }
  DepthSensorOptions bad;
  bad.columns = 0;
  EXPECT_FALSE(DepthSensor::Create(bad).ok());
}

TEST(PeopleTest, WalksStayFreeAndObservationsFlagTheirEnds) {
  const IndoorScene scene = GenerateIndoorScene({}, 5);
  const auto truth = RasterizeGroundFloor(scene, 0.05, true);
  ASSERT_TRUE(truth.ok());
  Random random(5);
  const std::vector<PersonWalk> walks = GenerateWalks(scene, *truth, 6, {}, &random);
  ASSERT_EQ(walks.size(), 6u);
  for (const PersonWalk& walk : walks) {
    for (const WalkSample& s : walk.samples) {
      EXPECT_EQ(At(*truth, s.position), grid::CellState::kFree) << walk.id;
    }
  }
  // A robot in the middle of the corridor with a 3 m range sees parts of the walks.
  const Point2 robot = 0.5 * (scene.corridor_min + scene.corridor_max);
  int seen = 0;
  for (const PersonWalk& walk : walks) {
    const auto observed = ObserveWalk(walk, *truth, robot, 3.0, 0.0, &random);
    if (!observed) continue;
    ++seen;
    EXPECT_GE(observed->points.size(), 2u);
    EXPECT_LE((observed->points.front().position - robot).norm(), 3.0 + 1e-9);
    EXPECT_EQ(observed->entered_view, (walk.samples.front().position - robot).norm() > 3.0 ||
                                          observed->points.front().stamp > 0.0);
  }
  EXPECT_GT(seen, 0);
}

}  // namespace
}  // namespace fleetmap::sim
