#include "bench/fleet/fleet_sim_report.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bench/fleet/fleet_sim.hpp"

namespace fleetmap::bench {
namespace {

// A robot placed at `fleet_from_map` whose map frame truly sits at `world_from_map`.
RobotPlacement Placed(const Pose2& world_from_map, const Pose2& fleet_from_map) {
  RobotPlacement placement;
  placement.true_world_from_map = world_from_map;
  placement.fleet_from_map = fleet_from_map;
  placement.placed_s = 3.0;
  placement.known_centroid = Point2(4.0, -2.0);
  return placement;
}

TEST(FleetSimReportTest, PlacementErrorIsZeroForTheTruePlacement) {
  const Pose2 world_from_anchor{12.0, -30.0, 1.0};
  const Pose2 world_from_map{-25.0, 8.0, -2.2};
  const Pose2 truth = Pose2::FromTransform(world_from_anchor.ToTransform().inverse() *
                                           world_from_map.ToTransform());
  const auto error = PlacementErrorOf(Placed(world_from_map, truth), world_from_anchor, 0.05);
  ASSERT_TRUE(error.has_value());
  EXPECT_NEAR(error->cells, 0.0, 1e-9);
  EXPECT_NEAR(error->yaw_deg, 0.0, 1e-9);
}

TEST(FleetSimReportTest, PlacementErrorIsMeasuredAtTheKnownCellsCentroid) {
  // The anchor is the world frame; the true placement is world_from_map itself.
  const Pose2 world_from_map{3.0, 1.0, 0.5};
  // Off by 10 cm along x: 2 cells of 5 cm wherever the centroid is.
  Pose2 shifted = world_from_map;
  shifted.x += 0.1;
  auto error = PlacementErrorOf(Placed(world_from_map, shifted), Pose2{}, 0.05);
  ASSERT_TRUE(error.has_value());
  EXPECT_NEAR(error->cells, 2.0, 1e-9);
  EXPECT_NEAR(error->yaw_deg, 0.0, 1e-9);
  // Turned by 1 degree about the map origin: the centroid (4, -2) moves by |c| * 2 sin(0.5 deg).
  Pose2 turned = world_from_map;
  turned.yaw += M_PI / 180.0;
  error = PlacementErrorOf(Placed(world_from_map, turned), Pose2{}, 0.05);
  ASSERT_TRUE(error.has_value());
  EXPECT_NEAR(error->cells, std::sqrt(20.0) * 2.0 * std::sin(M_PI / 360.0) / 0.05, 1e-9);
  EXPECT_NEAR(error->yaw_deg, 1.0, 1e-9);
}

TEST(FleetSimReportTest, NoPlacementErrorForARobotNeverPlaced) {
  RobotPlacement placement = Placed(Pose2{1.0, 2.0, 3.0}, Pose2{});
  placement.placed_s.reset();
  EXPECT_FALSE(PlacementErrorOf(placement, Pose2{}, 0.05).has_value());
}

TEST(FleetSimReportTest, UnknownPoseFramesAreSeededAndFarFromTheTerrainFrame) {
  const std::vector<Pose2> frames = UnknownPoseFrames(7, 8);
  ASSERT_EQ(frames.size(), 8u);
  EXPECT_EQ(frames, UnknownPoseFrames(7, 8));
  EXPECT_NE(frames, UnknownPoseFrames(8, 8));
  for (const Pose2& frame : frames) {
    EXPECT_GE(frame.translation().norm(), 10.0 - 1e-9);
    EXPECT_LE(frame.translation().norm(), 50.0 + 1e-9);
    EXPECT_GE(frame.yaw, -M_PI);
    EXPECT_LE(frame.yaw, M_PI);
  }
}

}  // namespace
}  // namespace fleetmap::bench
