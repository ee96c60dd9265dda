// The stairs and door detectors on points from the simulated depth camera (common/sim).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/extrapolation/door_detector.hpp"
#include "common/extrapolation/stairs_detector.hpp"
#include "common/sim/depth_sensor.hpp"
#include "common/sim/indoor_scene_generator.hpp"

namespace fleetmap::extrapolation {
namespace {

PointCloud Capture(const sim::IndoorScene& scene, const sim::CameraPose& camera, uint32_t seed) {
  const auto sensor = sim::DepthSensor::Create({});
  EXPECT_TRUE(sensor.ok());
  sim::Random random(seed);
  const std::vector<Eigen::Vector3d> points =
      sensor->Capture(sim::SceneBoxes(scene), camera, &random);
  return PointCloud(points.begin(), points.end());
}

TEST(StairsDetectorTest, RecoversFootDirectionAndWidthFromSimulatedPoints) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const sim::IndoorScene scene = sim::GenerateIndoorScene({}, seed);
    const sim::SceneStairs& truth = scene.stairs;
    sim::CameraPose camera;
    camera.pose = Pose2{truth.foot.x() - 2.5, truth.foot.y() + 0.2, 0.1};
    const std::vector<DetectedStairs> found = DetectStairs(Capture(scene, camera, seed));
    ASSERT_EQ(found.size(), 1u) << "seed " << seed;
    const scene::StairsEntity& s = found[0].entity;
    EXPECT_LT((s.position - truth.foot).norm(), 0.25) << "seed " << seed;
    EXPECT_GT(s.ascending.dot(truth.ascending), std::cos(5.0 * std::numbers::pi / 180.0))
        << "seed " << seed;
    EXPECT_NEAR(s.step_width, truth.width, 0.2) << "seed " << seed;
    EXPECT_NEAR(s.position.x() + s.run_length, truth.top().x(), 0.5) << "seed " << seed;
  }
}

TEST(StairsDetectorTest, NoStairsInAFlatCorridor) {
  const sim::IndoorScene scene = sim::GenerateIndoorScene({}, 4);
  sim::CameraPose camera;
  camera.pose =
      Pose2{scene.corridor_min.x() + 5.0, scene.stairs.foot.y(), std::numbers::pi};  // looking west
  EXPECT_TRUE(DetectStairs(Capture(scene, camera, 4)).empty());
}

TEST(DoorDetectorTest, FindsClosedDoorsAndTheirHingeSide) {
  sim::IndoorSceneOptions options;
  options.closed_door_probability = 1.0;
  int total = 0, checked = 0, hinge_right = 0;
  for (uint32_t seed : {5u, 6u}) {
    const sim::IndoorScene scene = sim::GenerateIndoorScene(options, seed);
    for (const sim::SceneDoor& door : scene.doors) {
      ++total;
      // Look at the door from 1.8 m along the corridor, from its centre line.
      const double y = 0.5 * (scene.corridor_min.y() + scene.corridor_max.y());
      const double dx = door.center().x() > scene.corridor_min.x() + 3.0 ? -1.8 : 1.8;
      const Point2 eye(door.center().x() + dx, y);
      const Vector2 look = door.center() - eye;
      sim::CameraPose camera;
      camera.pose = Pose2{eye.x(), eye.y(), std::atan2(look.y(), look.x())};
      const std::vector<DetectedDoor> found = DetectDoors(Capture(scene, camera, seed), eye);
      const DetectedDoor* match = nullptr;
      for (const DetectedDoor& d : found) {
        // The same door: centre and width (a door seen partly hidden comes out narrower).
        if ((d.entity.center() - door.center()).norm() < 0.3 &&
            std::abs(d.entity.width() - door.width()) < 0.2) {
          match = &d;
        }
      }
      if (match == nullptr) continue;
      ++checked;
      EXPECT_GT(match->entity.opening_direction.dot(door.room_side), 0.9);
      hinge_right += (match->entity.hinge - door.hinge).norm() < 0.3;
    }
  }
  ASSERT_GE(total, 8);
  ASSERT_GE(checked, 0.8 * total);
  EXPECT_GE(hinge_right, checked - 1);
}

}  // namespace
}  // namespace fleetmap::extrapolation
