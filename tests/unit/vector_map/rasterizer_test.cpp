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
  RasterizerOptions options;
  options.use_half_width = false;
  const OccupancyGrid out = *Rasterizer(options).Rasterize(map, like);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 12; ++x) {
      const bool near = x >= 2 && x <= 8 && y >= 2 && y <= 4;
      const bool end_cap = (x == 1 || x == 9) && y == 3;
      EXPECT_EQ(out.StateAt(x, y), near || end_cap ? CellState::kOccupied : CellState::kUnknown)
          << x << "," << y;
    }
  }
}

TEST(RasterizerTest, HalfWidthGivesAWallBackItsThickness) {
  const OccupancyGrid like(20, 11, 1.0);
  const CellFrame frame(like);
  VectorMap map;
  map.epsilon = 1.5;
  // A centre line at y = 5 standing for a wall three cells thick (y = 4..6), and a thin one at
  // y = 1 (half width 0: the default half cell, one row).
  map.obstacles.push_back(
      Polyline{{frame.ToMap(Point2(3, 5)), frame.ToMap(Point2(15, 5))}, false, 1.0});
  map.obstacles.push_back(Polyline{{frame.ToMap(Point2(3, 1)), frame.ToMap(Point2(15, 1))}});
  const OccupancyGrid out = *Rasterizer().Rasterize(map, like);
  for (int y = 0; y < 11; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool thick = (x >= 3 && x <= 15 && y >= 4 && y <= 6) || ((x == 2 || x == 16) && y == 5);
      const bool thin = x >= 3 && x <= 15 && y == 1;
      EXPECT_EQ(out.StateAt(x, y), thick || thin ? CellState::kOccupied : CellState::kUnknown)
          << x << "," << y;
    }
  }
}

TEST(RasterizerTest, VectorizedWallsComeBackAtTheirThickness) {
  for (int thickness = 1; thickness <= 3; ++thickness) {
    OccupancyGrid grid(60, 20, 0.05, {}, grid::kFreeValue);
    testing::FillRect(grid, 5, 8, 54, 8 + thickness - 1, grid::kOccupiedValue);
    const VectorMap map = *Vectorizer().Vectorize(grid);
    const OccupancyGrid back = *Rasterizer().Rasterize(map, grid);
    int wrong = 0;
    for (int y = 0; y < 20; ++y) {
      for (int x = 0; x < 60; ++x) {
        wrong += (back.StateAt(x, y) == CellState::kOccupied) !=
                 (grid.StateAt(x, y) == CellState::kOccupied);
      }
    }
    // 3: exact (a centre line on the middle row, half width 1). 1: exact but for the two end
    // cells (thinning shortens a line end by a cell; the half-cell radius does not reach back).
    // 2: one row too many or too few (a centre line on cell centres is symmetric about it).
    const int allowed[] = {0, 2, 52, 0};
    EXPECT_LE(wrong, allowed[thickness]) << "thickness " << thickness;
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
  RasterizerOptions fixed;
  fixed.use_half_width = false;
  EXPECT_FALSE(Rasterizer(fixed).Rasterize(VectorMap{}, 3, 3, 0.05, {}).ok());
  EXPECT_TRUE(Rasterizer().Rasterize(VectorMap{}, 3, 3, 0.05, {}).ok());
  const OccupancyGrid empty = *Rasterizer().Rasterize(map, 0, 0, 0.05, {});
  EXPECT_TRUE(empty.empty());
}

}  // namespace
}  // namespace fleetmap::vector_map
