#include "common/extrapolation/ransac_plane.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/extrapolation/voxel_filter.hpp"

namespace fleetmap::extrapolation {
namespace {

// 600 points on the plane z = 0.5 x + 1 (tilt atan(0.5)), 1 cm noise, among 400 outliers in a
// 4 m cube.
PointCloud PlaneWithOutliers() {
  std::mt19937 engine(3);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  PointCloud cloud;
  for (int i = 0; i < 600; ++i) {
    const double x = uniform(engine), y = uniform(engine);
    cloud.push_back(Point3(x, y, 0.5 * x + 1.0 + noise(engine)));
  }
  for (int i = 0; i < 400; ++i) {
    cloud.push_back(Point3(uniform(engine), uniform(engine), uniform(engine)));
  }
  return cloud;
}

TEST(RansacPlaneTest, FindsAKnownPlaneAmongOutliers) {
  const PointCloud cloud = PlaneWithOutliers();
  RansacOptions options;
  options.distance_threshold = 0.03;
  options.min_inliers = 100;
  const auto fit = FitPlaneRansac(cloud, options);
  ASSERT_TRUE(fit);
  const Vector3 expected = Vector3(-0.5, 0.0, 1.0).normalized();
  EXPECT_GT(fit->plane.normal.dot(expected), std::cos(1.0 * std::numbers::pi / 180.0));
  EXPECT_NEAR(fit->plane.Distance(Point3(0, 0, 1)), 0.0, 0.01);
  EXPECT_NEAR(fit->plane.Tilt(), std::atan(0.5), 0.02);
  // Nearly all 600 plane points, and few outliers (those that happen to lie in the band).
  EXPECT_GE(fit->inliers.size(), 590u);
  EXPECT_LE(fit->inliers.size(), 630u);
}

TEST(RansacPlaneTest, TiltConstraintRejectsThePlane) {
  RansacOptions options;
  options.min_inliers = 100;
  options.min_tilt = 1.3;  // only near-vertical planes: the sloped plane must not come back
  const auto fit = FitPlaneRansac(PlaneWithOutliers(), options);
  if (fit) {
    EXPECT_LT(fit->inliers.size(), 150u);
    EXPECT_GE(fit->plane.Tilt(), 1.3);
  }
}

TEST(RansacPlaneTest, ScoresOnASubsampleButCountsEveryInlier) {
  PointCloud cloud;
  for (int k = 0; k < 50; ++k) {
    const PointCloud part = PlaneWithOutliers();
    cloud.insert(cloud.end(), part.begin(), part.end());
  }
  RansacOptions options;
  options.min_inliers = 100;
  options.max_scored_points = 2000;  // 25 x fewer than the cloud
  const auto fit = FitPlaneRansac(cloud, options);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->plane.Tilt(), std::atan(0.5), 0.02);
  EXPECT_GE(fit->inliers.size(), 50u * 590u);
}

TEST(RansacPlaneTest, TooFewPointsGiveNothing) {
  EXPECT_FALSE(FitPlaneRansac({Point3(0, 0, 0), Point3(1, 0, 0)}, {}));
  EXPECT_FALSE(FitPlaneRansac({}, {}));
}

TEST(VoxelFilterTest, OnePointPerVoxelAtTheCentroid) {
  const PointCloud cloud = {Point3(0.01, 0.01, 0.01), Point3(0.03, 0.03, 0.03),
                            Point3(0.51, 0.0, 0.0), Point3(std::nan(""), 0, 0)};
  const PointCloud out = VoxelFilter(cloud, 0.1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[0].isApprox(Point3(0.02, 0.02, 0.02)));
  EXPECT_TRUE(out[1].isApprox(Point3(0.51, 0.0, 0.0)));
}

}  // namespace
}  // namespace fleetmap::extrapolation
