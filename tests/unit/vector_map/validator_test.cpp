#include "common/vector_map/validator.hpp"

#include <gtest/gtest.h>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/vectorizer.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

using grid::OccupancyGrid;

ValidationReport Check(const VectorMap& map, const OccupancyGrid& grid,
                       ValidatorOptions options = {}) {
  auto report = Validator(options).Validate(map, grid);
  EXPECT_TRUE(report.ok()) << report.status();
  return report.ok() ? *report : ValidationReport{};
}

TEST(ValidatorTest, AcceptsTheVectorizerOutput) {
  const OccupancyGrid grid = testing::FloorPlan();
  const VectorMap map = *Vectorizer().Vectorize(grid);
  const ValidationReport report = Check(map, grid);
  EXPECT_TRUE(report.ok());
  EXPECT_GT(report.delimitation_points, 0);
  EXPECT_LE(report.worst_point_distance, map.epsilon * (1 + 1e-9));
  EXPECT_LE(report.worst_segment_distance, map.epsilon * (1 + 1e-9));
}

TEST(ValidatorTest, CatchesAMovedPolyline) {
  const OccupancyGrid grid = testing::FloorPlan();
  VectorMap map = *Vectorizer().Vectorize(grid);
  size_t longest = 0;
  for (size_t i = 0; i < map.obstacles.size(); ++i) {
    if (map.obstacles[i].points.size() > map.obstacles[longest].points.size()) longest = i;
  }
  for (Point2& p : map.obstacles[longest].points) p += Point2(0.2, 0.2);  // 4 cells
  const ValidationReport report = Check(map, grid);
  EXPECT_FALSE(report.ok());
  EXPECT_GT(report.uncovered_points, 0);
  EXPECT_GT(report.discontinuous_segments, 0);
  EXPECT_GT(report.worst_point_distance, map.epsilon);
}

TEST(ValidatorTest, CatchesAMissingPolylineAndAnInventedWall) {
  const OccupancyGrid grid = testing::FloorPlan();
  VectorMap map = *Vectorizer().Vectorize(grid);
  VectorMap missing = map;
  missing.obstacles.erase(missing.obstacles.begin());
  EXPECT_GT(Check(missing, grid).uncovered_points, 0);
  EXPECT_EQ(Check(missing, grid).discontinuous_segments, 0);

  VectorMap invented = map;
  const CellFrame frame(grid);
  invented.obstacles.push_back(
      Polyline{{frame.ToMap(Point2(30, 60)), frame.ToMap(Point2(50, 60))}});
  const ValidationReport report = Check(invented, grid);
  EXPECT_EQ(report.uncovered_points, 0);
  EXPECT_EQ(report.discontinuous_segments, 1);
}

TEST(ValidatorTest, ContinuityIsExactBetweenTwoCells) {
  // Two occupied cells three cells apart; a segment joining their centres is continuous iff the
  // two epsilon-discs meet, i.e. epsilon >= 1.5 cells.
  OccupancyGrid grid(8, 3, 1.0, {}, grid::kFreeValue);
  grid.at(2, 1) = grid::kOccupiedValue;
  grid.at(5, 1) = grid::kOccupiedValue;
  const CellFrame frame(grid);
  VectorMap map;
  map.resolution = 1.0;
  map.obstacles.push_back(Polyline{{frame.ToMap(Point2(2, 1)), frame.ToMap(Point2(5, 1))}});
  map.epsilon = 1.5;
  EXPECT_TRUE(Check(map, grid).ok());
  map.epsilon = 1.49;
  const ValidationReport report = Check(map, grid);
  EXPECT_EQ(report.uncovered_points, 0);
  EXPECT_EQ(report.discontinuous_segments, 1);
  EXPECT_NEAR(report.worst_segment_distance, 1.5, 0.06);
}

TEST(ValidatorTest, PointObstacleCoversItsCell) {
  const OccupancyGrid grid = testing::GridFromPicture({"...", ".#.", "..."}, 0.1);
  const CellFrame frame(grid);
  VectorMap map;
  map.epsilon = DefaultEpsilon(0.1);
  map.obstacles.push_back(Polyline{{frame.ToMap(Point2(1, 1))}});
  const ValidationReport report = Check(map, grid);
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.segments, 1);
  EXPECT_EQ(report.delimitation_points, 1);
}

TEST(ValidatorTest, RejectsMissingEpsilon) {
  const OccupancyGrid grid(3, 3, 0.1);
  EXPECT_EQ(Validator().Validate(VectorMap{}, grid).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace fleetmap::vector_map
