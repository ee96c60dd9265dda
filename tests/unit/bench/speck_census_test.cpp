#include "bench/objects/speck_census.hpp"

#include <gtest/gtest.h>

#include "bench/objects/small_piece_experiment.hpp"

namespace fleetmap::bench {
namespace {

// A 10 x 10 m free floor at 5 cm with a wall along x = 0 and an unknown patch on the right.
grid::OccupancyGrid FreeFloor() {
  grid::OccupancyGrid map(200, 200, 0.05, Pose2{}, grid::kFreeValue);
  for (int y = 0; y < 200; ++y) map.at(0, y) = map.at(1, y) = grid::kOccupiedValue;
  for (int y = 0; y < 200; ++y) {
    for (int x = 160; x < 200; ++x) map.at(x, y) = grid::kUnknownValue;
  }
  return map;
}

TEST(SpeckCensusTest, CountsLoneClustersInFreeSpaceBySizeAndShape) {
  grid::OccupancyGrid map = FreeFloor();
  map.at(50, 50) = grid::kOccupiedValue;                               // a lone speck
  for (int x = 80; x < 85; ++x) map.at(x, 50) = grid::kOccupiedValue;  // a strand of 5
  for (int y = 100; y < 102; ++y) {  // a 2 x 2 blob: what a bin looks like
    for (int x = 100; x < 102; ++x) map.at(x, y) = grid::kOccupiedValue;
  }
  map.at(4, 150) = grid::kOccupiedValue;    // beside the wall: not alone
  map.at(180, 100) = grid::kOccupiedValue;  // in unknown space: not counted
  const SpeckCensus census = CountLoneSpecks(map);
  EXPECT_EQ(census.lone_specks, 1);
  EXPECT_EQ(census.lone_clusters, 2);
  EXPECT_EQ(census.lone_compact, 1);
  EXPECT_NEAR(census.free_area_m2, (158 * 200 - 5 - 4 - 2) * 0.0025, 1e-6);
  EXPECT_NEAR(census.Per100m2(census.lone_clusters), 200.0 / census.free_area_m2, 1e-9);
}

TEST(SpeckCensusTest, TwoSpecksCloserThanTheIsolationRadiusAreNeitherAlone) {
  grid::OccupancyGrid map = FreeFloor();
  map.at(50, 50) = grid::kOccupiedValue;
  map.at(55, 50) = grid::kOccupiedValue;  // 0.25 m away
  EXPECT_EQ(CountLoneSpecks(map).lone_specks, 0);
  SpeckCensusOptions tight;
  tight.isolation_m = 0.1;
  EXPECT_EQ(CountLoneSpecks(map, tight).lone_specks, 2);
}

TEST(SpeckCensusTest, ClustersLargerThanTheLimitAreFurnitureNotSpecks) {
  grid::OccupancyGrid map = FreeFloor();
  for (int y = 60; y < 63; ++y) {
    for (int x = 60; x < 63; ++x) map.at(x, y) = grid::kOccupiedValue;  // 9 cells
  }
  EXPECT_EQ(CountLoneSpecks(map).lone_clusters, 0);
  SpeckCensusOptions larger;
  larger.max_cells = 9;
  EXPECT_EQ(CountLoneSpecks(map, larger).lone_clusters, 1);
  EXPECT_EQ(CountLoneSpecks(map, larger).lone_compact, 0);  // more than 7 cells
}

// The census of the benchmark's own noise grows with the speck density it was given.
TEST(SpeckCensusTest, TheBenchmarksNoiseCountsMoreAtHigherDensity) {
  sim::Random random(7);
  SpeckCensus clean, light, heavy;
  for (int k = 0; k < 5; ++k) {
    clean.Add(CountLoneSpecks(SpeckledFloor(0.0, &random)));
    light.Add(CountLoneSpecks(SpeckledFloor(2.0, &random)));
    heavy.Add(CountLoneSpecks(SpeckledFloor(10.0, &random)));
  }
  EXPECT_EQ(clean.lone_specks + clean.lone_clusters, 0);
  EXPECT_GT(light.lone_specks + light.lone_clusters, 0);
  EXPECT_GT(heavy.lone_specks + heavy.lone_clusters, light.lone_specks + light.lone_clusters);
}

}  // namespace
}  // namespace fleetmap::bench
