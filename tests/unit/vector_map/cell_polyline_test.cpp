#include "common/vector_map/cell_polyline.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fleetmap::vector_map {
namespace {

CellPolyline Open(std::vector<Point2> points) {
  CellPolyline polyline;
  polyline.points = std::move(points);
  return polyline;
}

TEST(CellPolylineTest, PolylinesSharingAnEndAreJoined) {
  // A corner: one polyline of three vertices, the shared vertex stored once.
  const auto merged = MergeAtSharedEnds({Open({{0, 0}, {10, 0}}), Open({{10, 0}, {10, 8}})});
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].points.size(), 3u);
}

TEST(CellPolylineTest, NoJoinMakesAHairpinAndPolylinesAreCutAtOne) {
  // The two faces of a wall meeting at its end want different half widths.
  EXPECT_TRUE(IsHairpin({0, 0}, {10, 0}, {2, 1}));
  EXPECT_FALSE(IsHairpin({0, 0}, {10, 0}, {10, 8}));  // a right angle is a corner
  const auto merged = MergeAtSharedEnds({Open({{0, 0}, {10, 0}}), Open({{10, 0}, {2, 1}})});
  EXPECT_EQ(merged.size(), 2u);
  const auto split = SplitAtHairpins({Open({{0, 0}, {10, 0}, {2, 1}, {2, 5}})});
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].points, (std::vector<Point2>{{0, 0}, {10, 0}}));
  EXPECT_EQ(split[1].points, (std::vector<Point2>{{10, 0}, {2, 1}, {2, 5}}));
}

}  // namespace
}  // namespace fleetmap::vector_map
