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

// Free space may overlap obstacles (the rasterizer paints them over it), never unknown space: with
// outlines left unsimplified, no cell the grid calls free comes back unknown and no unknown cell
// comes back free. (At free_epsilon the outline may cut a corner between free and unknown cells.)
void ExpectFreeSpaceKept(const OccupancyGrid& grid, const OccupancyGrid& back) {
  int lost_free = 0;
  int invented_free = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const CellState was = grid.StateAt(x, y);
      const CellState now = back.StateAt(x, y);
      lost_free += was == CellState::kFree && now == CellState::kUnknown ? 1 : 0;
      invented_free += was == CellState::kUnknown && now == CellState::kFree ? 1 : 0;
    }
  }
  EXPECT_EQ(lost_free, 0);
  EXPECT_EQ(invented_free, 0);
}

TEST(RasterizerTest, ObstaclesInsideFreeSpaceCostNoHoles) {
  // A room (walls between free and unknown space) with a short wall, a pillar and a speck inside.
  OccupancyGrid grid(60, 40, 0.05, {}, grid::kUnknownValue);
  testing::FillRect(grid, 5, 5, 54, 34, grid::kOccupiedValue);
  testing::FillRect(grid, 6, 6, 53, 33, grid::kFreeValue);
  testing::FillRect(grid, 20, 6, 20, 20, grid::kOccupiedValue);
  testing::FillRect(grid, 35, 15, 37, 17, grid::kOccupiedValue);
  grid.at(45, 28) = grid::kOccupiedValue;
  const VectorMap map = *Vectorizer().Vectorize(grid);
  ASSERT_EQ(map.free_space.size(), 1u);
  EXPECT_TRUE(map.free_space[0].holes.empty());
  // The outline may run inside the walls, so a rectangle needs no more than its corners.
  EXPECT_LE(map.free_space[0].outer.size(), 6u);
  ExpectFreeSpaceKept(grid, *Rasterizer().Rasterize(map, grid));
  VectorizerOptions exact;
  exact.free_epsilon = 0.001;
  const VectorMap exact_map = *Vectorizer(exact).Vectorize(grid);
  EXPECT_TRUE(exact_map.free_space[0].holes.empty());
  ExpectFreeSpaceKept(grid, *Rasterizer().Rasterize(exact_map, grid));
}

TEST(RasterizerTest, UnknownHoleNextToAWallStaysUnknown) {
  OccupancyGrid grid(40, 30, 0.05, {}, grid::kFreeValue);
  testing::FillRect(grid, 10, 10, 25, 10, grid::kOccupiedValue);  // a wall
  testing::FillRect(grid, 14, 11, 20, 15, grid::kUnknownValue);   // unseen space behind it
  testing::FillRect(grid, 30, 20, 33, 23, grid::kUnknownValue);   // an unseen patch
  VectorizerOptions exact;
  exact.free_epsilon = 0.001;
  const VectorMap map = *Vectorizer(exact).Vectorize(grid);
  ASSERT_EQ(map.free_space.size(), 1u);
  EXPECT_EQ(map.free_space[0].holes.size(), 2u);
  ExpectFreeSpaceKept(grid, *Rasterizer().Rasterize(map, grid));
}

TEST(RasterizerTest, FreeSpaceOfAFloorPlanIsCheap) {
  const OccupancyGrid grid = testing::FloorPlan();
  const VectorMap map = *Vectorizer().Vectorize(grid);
  size_t rings = 0;
  for (const FreePolygon& polygon : map.free_space) rings += 1 + polygon.holes.size();
  // Measured: 2 rings, 8 vertices (the room and the space beyond its open side; no holes).
  EXPECT_LE(rings, 2u);
  EXPECT_LE(map.FreeVertexCount(), 10u);
  VectorizerOptions exact;
  exact.free_epsilon = 0.001;
  ExpectFreeSpaceKept(grid, *Rasterizer().Rasterize(*Vectorizer(exact).Vectorize(grid), grid));
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
