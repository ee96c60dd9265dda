#include "common/vector_map/rasterizer.hpp"

#include <gtest/gtest.h>

#include "common/metrics/map_quality.hpp"
#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/vectorizer.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

using grid::CellState;
using grid::OccupancyGrid;

TEST(RasterizerTest, OccupiesCellsWithinHalfEpsilonOfAnEdge) {
  const OccupancyGrid like(12, 7, 1.0);
  const CellFrame frame(like);
  VectorMap map;
  map.epsilon = 2.0;  // radius 1 cell
  map.obstacles.push_back(Polyline{{frame.ToMap(Point2(2, 3)), frame.ToMap(Point2(8, 3))}});
  const OccupancyGrid out = *Rasterizer().Rasterize(map, like);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 12; ++x) {
      const bool near = x >= 2 && x <= 8 && y >= 2 && y <= 4;
      const bool end_cap = (x == 1 || x == 9) && y == 3;
      EXPECT_EQ(out.StateAt(x, y), near || end_cap ? CellState::kOccupied : CellState::kUnknown)
          << x << "," << y;
    }
  }
}

TEST(RasterizerTest, FreePolygonWithHoleRebuildsTheRegion) {
  OccupancyGrid grid(30, 20, 0.05, {}, grid::kUnknownValue);
  testing::FillRect(grid, 3, 2, 25, 15, grid::kFreeValue);
  testing::FillRect(grid, 10, 6, 14, 9, grid::kUnknownValue);
  VectorizerOptions options;
  options.free_epsilon = 0.001;
  const VectorMap map = *Vectorizer(options).Vectorize(grid);
  ASSERT_EQ(map.free_space.size(), 1u);
  EXPECT_EQ(map.free_space[0].holes.size(), 1u);
  EXPECT_EQ(*Rasterizer().Rasterize(map, grid), grid);
}

TEST(RasterizerTest, RoundTripOfAFloorPlanScoresHigh) {
  const OccupancyGrid grid = testing::FloorPlan();
  const VectorMap map = *Vectorizer().Vectorize(grid);
  const OccupancyGrid back = *Rasterizer().Rasterize(map, grid);
  const auto scores = *metrics::CompareMaps(back, grid);
  EXPECT_GE(*scores.map_score, 90.0);  // centre lines rasterize thinner than thick walls
  EXPECT_GE(*scores.occupied_picture_distance, 99.0);
  EXPECT_GE(*scores.unoccupied_picture_distance, 99.0);
}

TEST(RasterizerTest, RejectsBadGeometry) {
  VectorMap map;
  map.epsilon = 0.1;
  EXPECT_FALSE(Rasterizer().Rasterize(map, -1, 3, 0.05, {}).ok());
  EXPECT_FALSE(Rasterizer().Rasterize(map, 3, 3, 0.0, {}).ok());
  EXPECT_FALSE(Rasterizer().Rasterize(VectorMap{}, 3, 3, 0.05, {}).ok());
  const OccupancyGrid empty = *Rasterizer().Rasterize(map, 0, 0, 0.05, {});
  EXPECT_TRUE(empty.empty());
}

}  // namespace
}  // namespace fleetmap::vector_map
