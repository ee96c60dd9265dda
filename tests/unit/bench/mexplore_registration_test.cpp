#include "bench/register/mexplore_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bench/register/map_pair_generator.hpp"
#include "common/grid/map_io.hpp"

namespace fleetmap::bench {
namespace {

TEST(MexploreRegistrationTest, PlacesAnEasyPair) {
  const std::string path = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";
  StatusOr<grid::LoadedMap> loaded = grid::LoadMap(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  const grid::OccupancyGrid& a = loaded->grid;
  // B: most of the house, a quarter turn (no resampling loss) in a frame far away.
  const grid::OccupancyGrid crop = CropCells(a, 100, 80, 300, 320);
  Transform2 a_from_b;
  const grid::OccupancyGrid b =
      TurnIntoNewFrame(crop, std::numbers::pi / 2, Pose2{350.0, -120.0, 0.8}, &a_from_b);
  const MexploreRegistration r = RegisterLikeMexplore(a, b);
  ASSERT_TRUE(r.found);
  const Point2 centroid = KnownCentroid(b);
  EXPECT_LT((r.a_from_b.ToTransform() * centroid - a_from_b * centroid).norm(),
            3.0 * a.resolution());
  EXPECT_LT(std::abs(NormalizeAngle(r.a_from_b.yaw - Pose2::FromTransform(a_from_b).yaw)),
            2.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(r.scale, 1.0, 0.05);
}

TEST(MexploreRegistrationTest, FindsNothingWithoutFeatures) {
  const grid::OccupancyGrid blank(60, 60, 0.05, Pose2{}, grid::kFreeValue);
  EXPECT_FALSE(RegisterLikeMexplore(blank, blank).found);
}

}  // namespace
}  // namespace fleetmap::bench
