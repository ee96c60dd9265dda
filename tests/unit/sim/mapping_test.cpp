// Laser, log-odds mapping, error model and exploration on small synthetic worlds.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/sim/exploration_simulator.hpp"
#include "common/sim/laser_scanner.hpp"
#include "common/sim/occupancy_mapper.hpp"
#include "common/sim/random.hpp"
#include "common/sim/slam_error_model.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::sim {
namespace {

// A 10 x 4 m corridor at 5 cm: walls on rows 0..1 and 78..79 and columns 0..1 and 198..199.
grid::OccupancyGrid Corridor() {
  grid::OccupancyGrid grid(200, 80, 0.05, Pose2{}, grid::kFreeValue);
  for (int x = 0; x < 200; ++x) {
    for (int y : {0, 1, 78, 79}) grid.at(x, y) = grid::kOccupiedValue;
  }
  for (int y = 0; y < 80; ++y) {
    for (int x : {0, 1, 198, 199}) grid.at(x, y) = grid::kOccupiedValue;
  }
  return grid;
}

TEST(LaserScannerTest, RangesAgainstAKnownWall) {
  const grid::OccupancyGrid truth = Corridor();
  const LaserScanner laser =
      *LaserScanner::Create({.range_noise_stddev = 0.0, .outlier_probability = 0.0});
  EXPECT_EQ(laser.ray_count(), 181);
  // From (5, 2): the wall at y = 0.1 (its top face) is 1.9 m straight down, the right wall's
  // face at x = 9.9 is 4.9 m away.
  EXPECT_NEAR(laser.CastRay(truth, {5.0, 2.0}, -std::numbers::pi / 2), 1.9, 1e-6);
  EXPECT_NEAR(laser.CastRay(truth, {5.0, 2.0}, 0.0), 4.9, 1e-6);
  EXPECT_NEAR(laser.CastRay(truth, {5.0, 2.0}, -std::numbers::pi / 4), 1.9 * std::sqrt(2.0), 0.08);
  Random random(1);
  const LaserScan scan = laser.Scan(truth, {5.0, 2.0, 0.0}, &random);
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_NEAR(scan.ranges[90], 4.9, 1e-6);  // straight ahead
  EXPECT_NEAR(scan.ranges[0], 1.9, 1e-6);   // -90 degrees
}

TEST(LaserScannerTest, NoRaysIsAnError) {
  const StatusOr<LaserScanner> none = LaserScanner::Create({.angular_step = 0.0});
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("angular_step"), std::string::npos);
  EXPECT_FALSE(LaserScanner::Create({.field_of_view = 0.0}).ok());
}

TEST(OccupancyMapperTest, CorridorGivesOccupiedWallsAndFreeInterior) {
  const grid::OccupancyGrid truth = Corridor();
  const LaserScanner laser = *LaserScanner::Create({.field_of_view = 2.0 * std::numbers::pi - 0.01,
                                                    .angular_step = std::numbers::pi / 360.0,
                                                    .outlier_probability = 0.0});
  OccupancyMapper mapper = *OccupancyMapper::Create(200, 80, 0.05, Pose2{}, {});
  Random random(2);
  for (double x = 1.0; x <= 9.0; x += 0.5) {
    const Pose2 pose{x, 2.0, 0.0};
    mapper.Integrate(laser.Scan(truth, pose, &random), pose);
  }
  const grid::OccupancyGrid map = mapper.ToGrid();
  int wall_occupied = 0;
  int interior_free = 0;
  int interior = 0;
  for (int x = 20; x < 180; ++x) {
    wall_occupied += map.at(x, 1) == grid::kOccupiedValue;
    wall_occupied += map.at(x, 78) == grid::kOccupiedValue;
    for (int y = 4; y < 76; ++y) {
      ++interior;
      interior_free += map.at(x, y) == grid::kFreeValue;
    }
  }
  EXPECT_GE(wall_occupied, 2 * 160 * 95 / 100);
  EXPECT_GE(interior_free, interior * 99 / 100);
  EXPECT_EQ(map.at(100, 0), grid::kUnknownValue);  // behind the wall's face: never seen
}

TEST(SlamErrorModelTest, DriftOnlyWhenEnabled) {
  SlamErrorModel off = *SlamErrorModel::Create({.enabled = false}, 5);
  SlamErrorModel on = *SlamErrorModel::Create({.jitter_xy = 0.0, .jitter_yaw = 0.0}, 5);
  const Pose2 truth{3.0, 4.0, 0.5};
  double largest = 0.0;
  for (int i = 0; i < 200; ++i) {
    off.Advance(0.5);
    on.Advance(0.5);
    EXPECT_EQ(off.Belief(truth), truth);
    const Pose2 belief = on.Belief(truth);
    largest = std::max(largest, std::hypot(belief.x - truth.x, belief.y - truth.y));
  }
  EXPECT_GT(largest, 0.005);
  EXPECT_LT(largest, 0.5);
}

ExplorationResult ExploreOffice(uint32_t seed) {
  const Terrain terrain =
      TerrainGenerator::Create({.kind = TerrainKind::kOffice, .size = 10.0, .seed = seed})
          ->Generate();
  const grid::OccupancyGrid truth = *RasterizeTerrain(terrain, 0.05);
  ExplorationOptions options;
  options.seed = seed;
  const ExplorationSimulator simulator = *ExplorationSimulator::Create(options);
  const StatusOr<ExplorationResult> result = simulator.Run(truth, terrain.start);
  EXPECT_TRUE(result.ok()) << result.status();
  return *result;
}

TEST(ExplorationSimulatorTest, ExploresMostOfASmallOffice) {
  const Terrain terrain =
      TerrainGenerator::Create({.kind = TerrainKind::kOffice, .size = 10.0, .seed = 4})->Generate();
  const grid::OccupancyGrid truth = *RasterizeTerrain(terrain, 0.05);
  const ExplorationResult result = ExploreOffice(4);
  EXPECT_TRUE(result.explored);
  int64_t free_truth = 0;
  int64_t observed = 0;
  for (int y = 0; y < truth.height(); ++y) {
    for (int x = 0; x < truth.width(); ++x) {
      if (truth.at(x, y) != grid::kFreeValue) continue;
      ++free_truth;
      observed += result.map.at(x, y) != grid::kUnknownValue;
    }
  }
  EXPECT_GE(observed, free_truth * 80 / 100) << observed << " of " << free_truth;
}

TEST(ExplorationSimulatorTest, SameSeedSameMapBytes) {
  const ExplorationResult a = ExploreOffice(9);
  const ExplorationResult b = ExploreOffice(9);
  EXPECT_EQ(a.map.data(), b.map.data());
  EXPECT_EQ(a.scans, b.scans);
}

TEST(ExplorationSimulatorTest, RefusesAStartInsideAWall) {
  const ExplorationSimulator simulator = *ExplorationSimulator::Create({});
  const StatusOr<ExplorationResult> result = simulator.Run(Corridor(), {0.02, 0.02, 0.0});
  EXPECT_FALSE(result.ok());
}

}  // namespace
}  // namespace fleetmap::sim
