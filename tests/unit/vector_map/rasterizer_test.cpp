#include "common/vector_map/rasterizer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "common/metrics/map_quality.hpp"
#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
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

TEST(RasterizerTest, GeometryFarOffTheGridMarksNothingAndReturns) {
  // A tile rasterized under another tile's key lands this far away: cell coordinates beyond the
  // int range once made the cell walk span all of it (start-up hung on such a stored row).
  const OccupancyGrid like(40, 40, 0.05);
  VectorMap map;
  map.epsilon = 0.0707;
  for (const double far : {1e9, -1e9, 1e12}) {
    map.obstacles.push_back(Polyline{{Point2(far, 0.5), Point2(far + 1.0, 0.5)}});
    map.obstacles.push_back(Polyline{{Point2(0.5, far), Point2(0.5, far + 1.0)}});
    FreePolygon free;
    free.outer = {Point2(far, far), Point2(far + 1.0, far), Point2(far + 1.0, far + 1.0)};
    map.free_space.push_back(free);
  }
  const auto out = Rasterizer().Rasterize(map, like);
  ASSERT_TRUE(out.ok()) << out.status();
  for (const int8_t value : out->data()) ASSERT_EQ(value, grid::kUnknownValue);
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
    // All exact. 3: a centre line on the middle row, half width 1. 1: the line ends thinning
    // shortened are moved back onto their end cells (end_extender). 2: the centre line is moved
    // between the two rows (line_refit; on cell centres it painted one row too many or too few).
    EXPECT_EQ(wrong, 0) << "thickness " << thickness;
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

TEST(RasterizerTest, PaintedObstaclesInsideFreeSpaceCostNoHoles) {
  // A room (walls between free and unknown space) with a short wall, a pillar and a speck inside.
  OccupancyGrid grid(60, 40, 0.05, {}, grid::kUnknownValue);
  testing::FillRect(grid, 5, 5, 54, 34, grid::kOccupiedValue);
  testing::FillRect(grid, 6, 6, 53, 33, grid::kFreeValue);
  testing::FillRect(grid, 20, 6, 20, 20, grid::kOccupiedValue);
  testing::FillRect(grid, 35, 15, 37, 17, grid::kOccupiedValue);
  grid.at(45, 28) = grid::kOccupiedValue;
  const VectorMap map = *Vectorizer().Vectorize(grid);
  ASSERT_EQ(map.free_space.size(), 1u);
  // The speck and the walls cost nothing, and neither do the occupied cells the obstacles leave
  // unpainted (a corner of the pillar beyond its half width): they lie within epsilon of an edge,
  // which stands for them, so they may come back free.
  EXPECT_EQ(map.free_space[0].holes.size(), 0u);
  // The outline may run inside the walls, so a rectangle needs no more than its corners.
  EXPECT_LE(map.free_space[0].outer.size(), 6u);
  const OccupancyGrid back = *Rasterizer().Rasterize(map, grid);
  ExpectFreeSpaceKept(grid, back);
  EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, map, back), 0);
  VectorizerOptions exact;
  exact.free_epsilon = 0.001;
  const VectorMap exact_map = *Vectorizer(exact).Vectorize(grid);
  EXPECT_EQ(exact_map.free_space[0].holes.size(), 0u);
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
  // The two unknown patches only: thinning shortens the wall's centre line by a cell at each
  // end, and the line ends are moved back onto those end cells (end_extender), so they are
  // painted and need no hole of their own (they did before: 4 holes).
  EXPECT_EQ(map.free_space[0].holes.size(), 2u);
  const OccupancyGrid back = *Rasterizer().Rasterize(map, grid);
  ExpectFreeSpaceKept(grid, back);
  EXPECT_EQ(testing::OccupiedComeBackFree(grid, back), 0);
}

TEST(RasterizerTest, FreeSpaceOfAFloorPlanIsCheap) {
  const OccupancyGrid grid = testing::FloorPlan();
  const VectorMap map = *Vectorizer().Vectorize(grid);
  size_t rings = 0;
  for (const FreePolygon& polygon : map.free_space) rings += 1 + polygon.holes.size();
  // Measured: 9 rings, 41 vertices: the outline, the unknown patch, the solid blob (4 vertices)
  // and 6 small holes around occupied cells the obstacles leave unpainted (wall ends and corners,
  // the 4-cell wall's outer row). Before solid cells were guarded (they came back free): 2, 8.
  EXPECT_LE(rings, 9u);
  EXPECT_LE(map.FreeVertexCount(), 43u);
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

// Solid regions (occupied cells deep inside an obstacle) come back as their painted outline
// around an unknown inside, a hole of the free polygon; never free. The rest of the round trip is
// what it was: with straight outlines, no free cell comes back unknown and no unknown one free.
struct SolidCase {
  const char* name;
  OccupancyGrid grid;
  bool straight;  // outlines Douglas-Peucker keeps exactly
};

std::vector<SolidCase> SolidCases() {
  std::vector<SolidCase> cases;
  {
    // The block: 2 x 2 m inside free space.
    OccupancyGrid grid(80, 80, 0.05, {}, grid::kFreeValue);
    testing::FillRect(grid, 20, 20, 59, 59, grid::kOccupiedValue);
    cases.push_back({"block", grid, true});
  }
  {
    OccupancyGrid grid(80, 80, 0.05, {}, grid::kFreeValue);
    testing::FillRect(grid, 15, 15, 64, 34, grid::kOccupiedValue);
    testing::FillRect(grid, 15, 15, 34, 64, grid::kOccupiedValue);
    cases.push_back({"l_shape", grid, true});
  }
  {
    OccupancyGrid grid(80, 80, 0.05, {}, grid::kFreeValue);
    testing::DrawLine(grid, 40, 40, 40, 40, 17.0);  // a disc
    testing::DrawLine(grid, 10, 65, 70, 55, 4.3);   // a thick slanted bar
    cases.push_back({"blobs", grid, false});
  }
  {
    // Touching the map border on one, two and three sides; one against unknown space.
    OccupancyGrid grid(70, 60, 0.05, {}, grid::kFreeValue);
    testing::FillRect(grid, 0, 0, 19, 14, grid::kOccupiedValue);
    testing::FillRect(grid, 45, 10, 69, 30, grid::kOccupiedValue);
    testing::FillRect(grid, 20, 50, 35, 59, grid::kOccupiedValue);
    testing::FillRect(grid, 0, 40, 9, 59, grid::kUnknownValue);
    testing::FillRect(grid, 5, 30, 25, 45, grid::kOccupiedValue);
    // Not straight: the outline between free and unknown space is simplified (it may cut a corner).
    cases.push_back({"at_the_border", grid, false});
  }
  return cases;
}

TEST(RasterizerTest, SolidRegionsComeBackWithoutFreeCells) {
  for (const VectorizeMethod method : {VectorizeMethod::kDefault, VectorizeMethod::kPaper}) {
    for (const SolidCase& c : SolidCases()) {
      SCOPED_TRACE(std::string(c.name) + (method == VectorizeMethod::kPaper ? " paper" : ""));
      VectorizerOptions options;
      options.method = method;
      const VectorMap map = *Vectorizer(options).Vectorize(c.grid);
      const OccupancyGrid back = *Rasterizer().Rasterize(map, c.grid);
      EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(c.grid, map, back), 0);
      // A solid region costs one ring (its outline), not a fill.
      size_t rings = 0;
      for (const FreePolygon& polygon : map.free_space) rings += 1 + polygon.holes.size();
      EXPECT_LE(rings, 5u);
      if (c.straight) {
        EXPECT_LE(map.FreeVertexCount(), 40u);
      }
      // With outlines left unsimplified, free and unknown space come back as they were.
      VectorizerOptions exact = options;
      exact.free_epsilon = 0.001;
      const VectorMap exact_map = *Vectorizer(exact).Vectorize(c.grid);
      const OccupancyGrid exact_back = *Rasterizer().Rasterize(exact_map, c.grid);
      EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(c.grid, exact_map, exact_back), 0);
      ExpectFreeSpaceKept(c.grid, exact_back);
      if (c.straight) {
        ExpectFreeSpaceKept(c.grid, back);
      }
      if (method == VectorizeMethod::kPaper) continue;  // it may break epsilon-error (below)
      // The outline comes back: every boundary cell of a region (a 4-neighbour not occupied)
      // within one cell of an occupied cell of the round trip.
      for (int y = 0; y < c.grid.height(); ++y) {
        for (int x = 0; x < c.grid.width(); ++x) {
          if (c.grid.StateAt(x, y) != CellState::kOccupied) continue;
          bool boundary = false;
          for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            boundary |= c.grid.Contains(x + dx, y + dy) &&
                        c.grid.StateAt(x + dx, y + dy) != CellState::kOccupied;
          }
          if (!boundary) continue;
          bool near = false;
          for (int ny = y - 1; ny <= y + 1; ++ny) {
            for (int nx = x - 1; nx <= x + 1; ++nx) {
              near |= back.Contains(nx, ny) && back.StateAt(nx, ny) == CellState::kOccupied;
            }
          }
          EXPECT_TRUE(near) << x << "," << y;
        }
      }
    }
  }
}

TEST(RasterizerTest, SolidBlockIsAPaintedOutlineAroundAnUnknownInside) {
  const SolidCase block = SolidCases().front();
  const VectorMap map = *Vectorizer().Vectorize(block.grid);
  ASSERT_EQ(map.free_space.size(), 1u);
  ASSERT_EQ(map.free_space[0].holes.size(), 1u);
  EXPECT_EQ(map.free_space[0].outer.size(), 4u);
  EXPECT_EQ(map.free_space[0].holes[0].size(), 4u);
  const OccupancyGrid back = *Rasterizer().Rasterize(map, block.grid);
  EXPECT_EQ(back.StateAt(40, 40), CellState::kUnknown);
  EXPECT_EQ(back.StateAt(20, 40), CellState::kOccupied);
  EXPECT_EQ(back.StateAt(19, 40), CellState::kFree);
}

// Noise and solid blocks, whole and in quantised tiles: Douglas-Peucker shortcuts through the
// outlines must never uncover an occupied cell the obstacles leave unpainted.
TEST(RasterizerTest, NoOccupiedCellComesBackFreeOnNoise) {
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    OccupancyGrid grid = testing::NoiseGrid(72, 64, 0.08 + 0.03 * (seed % 5), seed);
    testing::FillRect(grid, 5 + seed, 7, 20 + seed, 30, grid::kOccupiedValue);
    testing::DrawLine(grid, 40, 40, 60 - seed, 20 + seed, 3.4);
    for (const VectorizeMethod method : {VectorizeMethod::kDefault, VectorizeMethod::kPaper}) {
      VectorizerOptions options;
      options.method = method;
      const VectorMap map = *Vectorizer(options).Vectorize(grid);
      EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, map,
                                                              *Rasterizer().Rasterize(map, grid)),
                0);
      TiledVectorizeOptions tiled;
      tiled.tile_size = 0.8;  // 16 cells
      tiled.vectorizer = options;
      // Tile borders and the lattice off the grid's cell borders.
      Transform2 fleet_from_map = Transform2::Identity();
      fleet_from_map.translation() = Point2(0.33, -0.47);
      const VectorMap merged = VectorizeTiled(grid, fleet_from_map, tiled)->Merged();
      // Rasterized in the fleet frame, over the grid's cells.
      const Pose2 origin{grid.origin().x + 0.33, grid.origin().y - 0.47, 0.0};
      const OccupancyGrid back =
          *Rasterizer().Rasterize(merged, grid.width(), grid.height(), grid.resolution(), origin);
      EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, merged, back), 0);
    }
  }
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
