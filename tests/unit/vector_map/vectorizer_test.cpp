#include "common/vector_map/vectorizer.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "common/vector_map/validator.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

using grid::OccupancyGrid;
using testing::DrawLine;
using testing::FillRect;
using testing::GridFromPicture;

VectorMap VectorizeOrDie(const OccupancyGrid& grid, VectorizerOptions options = {}) {
  auto map = Vectorizer(options).Vectorize(grid);
  EXPECT_TRUE(map.ok()) << map.status();
  return map.ok() ? *map : VectorMap{};
}

ValidationReport ValidateOrDie(const VectorMap& map, const OccupancyGrid& grid) {
  auto report = Validator().Validate(map, grid);
  EXPECT_TRUE(report.ok()) << report.status();
  return report.ok() ? *report : ValidationReport{};
}

void ExpectValid(const VectorMap& map, const OccupancyGrid& grid) {
  const ValidationReport report = ValidateOrDie(map, grid);
  EXPECT_EQ(report.uncovered_points, 0) << "worst point distance " << report.worst_point_distance;
  EXPECT_EQ(report.discontinuous_segments, 0)
      << "worst segment distance " << report.worst_segment_distance;
}

TEST(VectorizerTest, EmptyGridGivesEmptyMap) {
  const OccupancyGrid grid(0, 0, 0.05);
  const VectorMap map = VectorizeOrDie(grid);
  EXPECT_TRUE(map.obstacles.empty());
  EXPECT_TRUE(map.free_space.empty());
  EXPECT_DOUBLE_EQ(map.epsilon, DefaultEpsilon(0.05));
}

TEST(VectorizerTest, AllUnknownGivesNothing) {
  const OccupancyGrid grid(17, 9, 0.05);
  const VectorMap map = VectorizeOrDie(grid);
  EXPECT_TRUE(map.obstacles.empty());
  EXPECT_TRUE(map.free_space.empty());
}

TEST(VectorizerTest, AllFreeGivesOneFreePolygon) {
  const OccupancyGrid grid(17, 9, 0.05, {}, grid::kFreeValue);
  const VectorMap map = VectorizeOrDie(grid);
  EXPECT_TRUE(map.obstacles.empty());
  ASSERT_EQ(map.free_space.size(), 1u);
  EXPECT_EQ(map.free_space[0].outer.size(), 4u);
  EXPECT_TRUE(map.free_space[0].holes.empty());
}

TEST(VectorizerTest, OneByOneOccupiedIsAPoint) {
  const OccupancyGrid grid(1, 1, 0.1, Pose2{1.0, 2.0, 0.0}, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  ASSERT_EQ(map.obstacles[0].points.size(), 1u);
  EXPECT_TRUE(map.obstacles[0].points[0].isApprox(Point2(1.05, 2.05)));
  ExpectValid(map, grid);
}

TEST(VectorizerTest, IsolatedCellIsAPointObstacle) {
  const OccupancyGrid grid = GridFromPicture({".....", ".....", "..#..", ".....", "....."});
  const VectorMap map = VectorizeOrDie(grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_EQ(map.obstacles[0].points.size(), 1u);
  EXPECT_EQ(map.ObstacleSegmentCount(), 0u);
  ExpectValid(map, grid);
}

// The cells of `grid` whose state `back` (a rasterized vector map) gets wrong.
int CellsChanged(const OccupancyGrid& grid, const OccupancyGrid& back) {
  int changed = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) changed += grid.StateAt(x, y) != back.StateAt(x, y);
  }
  return changed;
}

TEST(VectorizerTest, BlobsOneDiscPaintsAreOnePoint) {
  // A pair of cells and a 2 x 2 block: one point each, whose disc paints the blob exactly.
  const OccupancyGrid grid = GridFromPicture({"..........",  //
                                              ".##.......",  //
                                              "..........",  //
                                              "......##..",  //
                                              "......##..",  //
                                              ".........."});
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 2u);
  for (const Polyline& obstacle : map.obstacles) EXPECT_EQ(obstacle.points.size(), 1u);
  EXPECT_EQ(CellsChanged(grid, *Rasterizer().Rasterize(map, grid)), 0);
}

TEST(VectorizerTest, ARowOfThreeCellsStaysALine) {
  // One point 1 cell from both ends would satisfy both constraints, but its disc would paint the
  // two cells beside the middle one too: the line paints the row exactly, so it stays.
  const OccupancyGrid grid = GridFromPicture({".......", ".......", ".###...", "......."});
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_EQ(map.obstacles[0].points.size(), 2u);
  EXPECT_EQ(CellsChanged(grid, *Rasterizer().Rasterize(map, grid)), 0);
}

TEST(VectorizerTest, WallFourCellsThickIsDrawnByItsFaces) {
  // No centre line is within epsilon (sqrt 2 cells) of both faces of a wall four cells thick, and
  // hollowing keeps all of it, so the skeleton zigzags between the faces (56 vertices on this
  // wall). The two faces are a few vertices and paint the wall back nearly as well.
  OccupancyGrid grid(90, 30, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 10, 84, 13, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  EXPECT_LE(map.ObstacleVertexCount(), 8u);
  EXPECT_LE(CellsChanged(grid, *Rasterizer().Rasterize(map, grid)), 3);
}

TEST(VectorizerTest, AllOccupiedIsOutlinedAtTheGridBorder) {
  const OccupancyGrid grid(30, 20, 0.05, {}, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  EXPECT_LE(map.ObstacleVertexCount(), 6u);
}

class ThinWallTest : public ::testing::TestWithParam<int> {};

TEST_P(ThinWallTest, WallUpToThreeCellsIsOneCentreLine) {
  const int thickness = GetParam();
  OccupancyGrid grid(60, 20, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 8, 54, 8 + thickness - 1, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_EQ(map.obstacles[0].points.size(), 2u);
}

INSTANTIATE_TEST_SUITE_P(Thickness, ThinWallTest, ::testing::Values(1, 2, 3));

TEST(VectorizerTest, WallWithPocketsIsOneCentreLine) {
  // A wall three cells thick whose unseen middle row leaves a pocket of one or two cells every
  // few cells (SLAM maps of walls seen from both sides): one centre line, not a ladder of rings.
  OccupancyGrid grid(60, 20, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 8, 54, 10, grid::kOccupiedValue);
  for (int x = 8; x < 52; x += 5) {
    grid.at(x, 9) = grid::kUnknownValue;
    if (x % 10 == 3) grid.at(x + 1, 9) = grid::kUnknownValue;  // two-cell pockets at 13, 23, ...
  }
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_EQ(map.obstacles[0].points.size(), 2u);
}

TEST(VectorizerTest, VerticalAndDiagonalWallsAreCentreLines) {
  OccupancyGrid grid(80, 80, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 10, 5, 11, 70, grid::kOccupiedValue);
  DrawLine(grid, 20, 10, 70, 60, 0.75);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  EXPECT_EQ(map.obstacles.size(), 2u);
  EXPECT_LE(map.ObstacleVertexCount(), 5u);
}

TEST(VectorizerTest, ThickBlobGetsAnOutline) {
  OccupancyGrid grid(40, 40, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 8, 10, 30, 28, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  EXPECT_LE(map.ObstacleVertexCount(), 6u);
}

TEST(VectorizerTest, RoomWallsFormOneRing) {
  OccupancyGrid grid(50, 40, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 5, 44, 6, grid::kOccupiedValue);
  FillRect(grid, 5, 33, 44, 34, grid::kOccupiedValue);
  FillRect(grid, 5, 5, 6, 34, grid::kOccupiedValue);
  FillRect(grid, 43, 5, 44, 34, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 1u);
  EXPECT_TRUE(map.obstacles[0].closed);
  EXPECT_LE(map.obstacles[0].points.size(), 5u);
}

TEST(VectorizerTest, FloorPlanHoldsBothConstraints) {
  const OccupancyGrid grid = testing::FloorPlan();
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
}

TEST(VectorizerTest, NoiseHoldsBothConstraints) {
  for (const double density : {0.05, 0.2, 0.45, 0.7}) {
    for (uint32_t seed = 1; seed <= 3; ++seed) {
      const OccupancyGrid grid = testing::NoiseGrid(64, 48, density, seed);
      SCOPED_TRACE(::testing::Message() << "density " << density << " seed " << seed);
      ExpectValid(VectorizeOrDie(grid), grid);
    }
  }
}

TEST(VectorizerTest, LargerEpsilonGivesFewerVertices) {
  OccupancyGrid grid(100, 100, 0.05, {}, grid::kFreeValue);
  for (int k = 0; k < 8; ++k)
    DrawLine(grid, 50, 50, 50 + 45 * std::cos(k), 50 + 45 * std::sin(k), 1.0);
  DrawLine(grid, 5, 5, 95, 20, 0.6);
  const VectorMap fine = VectorizeOrDie(grid);
  VectorizerOptions coarse_options;
  coarse_options.epsilon = 0.15;
  const VectorMap coarse = VectorizeOrDie(grid, coarse_options);
  ExpectValid(fine, grid);
  ExpectValid(coarse, grid);
  EXPECT_LE(coarse.ObstacleVertexCount(), fine.ObstacleVertexCount());
}

TEST(VectorizerTest, CrossingWallsShareTheJunctionVertex) {
  OccupancyGrid grid(41, 41, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 20, 35, 20, grid::kOccupiedValue);
  FillRect(grid, 20, 5, 20, 35, grid::kOccupiedValue);
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  // Two straight lines through the crossing: 4 vertices (chains ending at the junction: 5-8).
  EXPECT_EQ(map.obstacles.size(), 2u);
  EXPECT_EQ(map.ObstacleVertexCount(), 4u);
}

TEST(VectorizerTest, SpecksInARowShareOneSegment) {
  OccupancyGrid grid(40, 10, 0.05, {}, grid::kFreeValue);
  for (int x = 5; x <= 33; x += 2) grid.at(x, 5) = grid::kOccupiedValue;  // 15 specks, gaps of 1
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  EXPECT_EQ(map.ObstacleVertexCount(), 2u);  // one segment instead of 15 point obstacles
}

TEST(VectorizerTest, PolylinesCarryTheWallHalfWidth) {
  OccupancyGrid grid(60, 30, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 5, 54, 7, grid::kOccupiedValue);    // 3 thick
  FillRect(grid, 5, 20, 54, 20, grid::kOccupiedValue);  // 1 thick
  const VectorMap map = VectorizeOrDie(grid);
  ExpectValid(map, grid);
  ASSERT_EQ(map.obstacles.size(), 2u);
  for (const Polyline& polyline : map.obstacles) {
    const bool thick = polyline.points[0].y() < 0.5;
    // Thick: at least the one cell to each side (a little more may buy the corner cells at the
    // line's ends). Thin: nothing beyond the rasterizer's half-cell default.
    if (thick) {
      EXPECT_GE(polyline.half_width, 0.05 - 1e-9);
    } else {
      EXPECT_EQ(polyline.half_width, 0.0);
    }
    EXPECT_LE(polyline.half_width, map.epsilon);
  }
}

// Quantised output ------------------------------------------------------------------------------

void ExpectOnLattice(const VectorMap& map, double quantum, const Point2& origin) {
  auto on = [&](const Point2& p) {
    for (const double k : {(p.x() - origin.x()) / quantum, (p.y() - origin.y()) / quantum}) {
      EXPECT_NEAR(k, std::round(k), 1e-6) << p.transpose();
    }
  };
  for (const Polyline& polyline : map.obstacles) {
    for (const Point2& p : polyline.points) on(p);
  }
  for (const FreePolygon& polygon : map.free_space) {
    for (const Point2& p : polygon.outer) on(p);
    for (const auto& hole : polygon.holes) {
      for (const Point2& p : hole) on(p);
    }
  }
}

// Line ends that thinning shortens: the polylines must paint them themselves, so they need no
// free-space hole. Before end_extender every thin wall left both end cells unpainted: 18 cells
// and 9 holes on this fixture (16 and 7 on the lattice); now 11 and 2.
TEST(VectorizerTest, LineEndsArePaintedByTheirPolylines) {
  OccupancyGrid grid(80, 60, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 5, 5, 30, 5, grid::kOccupiedValue);    // 1 cell thick, horizontal
  FillRect(grid, 40, 5, 40, 30, grid::kOccupiedValue);  // 1 cell thick, vertical
  FillRect(grid, 5, 15, 30, 17, grid::kOccupiedValue);  // 3 cells thick
  for (int k = 0; k < 15; ++k) grid.at(10 + k, 30 + k) = grid::kOccupiedValue;  // diagonal
  FillRect(grid, 50, 10, 70, 10, grid::kOccupiedValue);  // an L: two free ends and a corner
  FillRect(grid, 70, 10, 70, 40, grid::kOccupiedValue);
  for (const bool tiled : {false, true}) {
    SCOPED_TRACE(tiled ? "on the tile lattice" : "whole map");
    VectorizerOptions options;
    if (tiled) {
      options.quantum = TileQuantum(grid.resolution());
      options.lattice_origin = TileLatticeOrigin(grid.origin().translation(), options.quantum);
    }
    const VectorMap map = VectorizeOrDie(grid, options);
    ExpectValid(map, grid);
    VectorMap obstacles = map;
    obstacles.free_space.clear();
    const OccupancyGrid back = *Rasterizer().Rasterize(obstacles, grid);
    // Every cell of the straight walls and the diagonal is painted, ends included.
    int outside_l = 0;
    for (int y = 0; y < grid.height(); ++y) {
      for (int x = 0; x < 50; ++x) {
        outside_l += grid.StateAt(x, y) == grid::CellState::kOccupied &&
                     back.StateAt(x, y) != grid::CellState::kOccupied;
      }
    }
    EXPECT_EQ(outside_l, 0);
    // Known shortfall: the L's corner is simplified to a shortcut within epsilon whose thin band
    // misses ten cells of the horizontal arm (and one end cell that cannot be reached without
    // unpainting others). They lie within epsilon of the shortcut, so the free space may cover
    // them: they cost no hole, and no occupied cell farther from the obstacles comes back free.
    EXPECT_LE(testing::OccupiedLeftUnpainted(grid, back), 11);
    size_t holes = 0;
    for (const FreePolygon& polygon : map.free_space) holes += polygon.holes.size();
    EXPECT_EQ(holes, 0u);
    EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, map,
                                                            *Rasterizer().Rasterize(map, grid)),
              0);
  }
}

TEST(VectorizerTest, QuantisedOutputLiesOnTheLatticeAndHoldsBothConstraints) {
  const OccupancyGrid grid = testing::FloorPlan();
  for (const double quantum : {0.001, 0.0123, 0.02}) {
    VectorizerOptions options;
    options.quantum = quantum;
    options.lattice_origin = Point2(0.0037, -0.011);
    const VectorMap map = VectorizeOrDie(grid, options);
    SCOPED_TRACE(::testing::Message() << "quantum " << quantum);
    ExpectOnLattice(map, quantum, options.lattice_origin);
    ExpectValid(map, grid);
    EXPECT_GT(map.ObstacleVertexCount(), 0u);
  }
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const OccupancyGrid noise = testing::NoiseGrid(64, 48, 0.3, seed);
    VectorizerOptions options;
    options.quantum = 0.02;
    ExpectValid(VectorizeOrDie(noise, options), noise);
  }
}

TEST(VectorizerTest, CellLatticeKeepsTheFullEpsilon) {
  // A quantum dividing half a cell, with the origin on the cell lattice: every vertex is already a
  // lattice point, so the polylines are the unquantised ones (built with the full epsilon), not
  // the ones built with epsilon shrunk by the snapping move. (Line refit may still choose other
  // half-cell positions: on a lattice, half widths are rounded up to whole quanta.)
  std::vector<OccupancyGrid> grids = {testing::FloorPlan()};
  for (uint32_t seed = 1; seed <= 3; ++seed) grids.push_back(testing::NoiseGrid(64, 48, 0.3, seed));
  for (const OccupancyGrid& grid : grids) {
    const VectorMap plain = VectorizeOrDie(grid);
    VectorizerOptions on_cells;
    on_cells.quantum = grid.resolution() / 80;  // the codec's 10 m / 16000 on 5 cm cells
    const VectorMap aligned = VectorizeOrDie(grid, on_cells);
    ExpectValid(aligned, grid);
    ExpectOnLattice(aligned, on_cells.quantum, on_cells.lattice_origin);
    ASSERT_EQ(aligned.obstacles.size(), plain.obstacles.size());
    for (size_t k = 0; k < plain.obstacles.size(); ++k) {
      EXPECT_EQ(aligned.obstacles[k].points.size(), plain.obstacles[k].points.size()) << k;
    }
    // The same quantum a third of a quantum off the cells: still valid, built with less epsilon.
    VectorizerOptions off_cells = on_cells;
    off_cells.lattice_origin = Point2(on_cells.quantum / 3, 0.0);
    const VectorMap shifted = VectorizeOrDie(grid, off_cells);
    ExpectValid(shifted, grid);
    ExpectOnLattice(shifted, off_cells.quantum, off_cells.lattice_origin);
  }
}

TEST(VectorizerTest, RejectsAQuantumThatLeavesNoEpsilon) {
  const OccupancyGrid grid(10, 10, 0.05);
  VectorizerOptions options;
  options.quantum = 0.06;
  EXPECT_EQ(Vectorizer(options).Vectorize(grid).status().code(), StatusCode::kInvalidArgument);
  options.quantum = -1.0;
  EXPECT_EQ(Vectorizer(options).Vectorize(grid).status().code(), StatusCode::kInvalidArgument);
}

TEST(VectorizerTest, RejectsTinyEpsilonAndBadRect) {
  const OccupancyGrid grid(10, 10, 0.05);
  VectorizerOptions options;
  options.epsilon = 0.01;
  EXPECT_EQ(Vectorizer(options).Vectorize(grid).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(Vectorizer().VectorizeTile(grid, CellRect{5, 5, 6, 2}).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(VectorizerTest, PaperMethodRunsAndKeepsContinuityOfItsGraph) {
  const OccupancyGrid grid = testing::FloorPlan();
  VectorizerOptions options;
  options.method = VectorizeMethod::kPaper;
  const VectorMap paper = VectorizeOrDie(grid, options);
  const VectorMap ours = VectorizeOrDie(grid);
  EXPECT_GT(paper.ObstacleVertexCount(), 0u);
  EXPECT_LT(ours.ObstacleVertexCount(), paper.ObstacleVertexCount());
}

TEST(VectorizerTest, PaperMethodCanBreakTheEpsilonErrorConstraint) {
  // A gentle arc: each shortcut only checks the removed vertex, so folded points drift away.
  OccupancyGrid grid(200, 120, 0.05, {}, grid::kFreeValue);
  for (int x = 0; x < 200; ++x) grid.at(x, 10 + x * x / 400) = grid::kOccupiedValue;
  VectorizerOptions options;
  options.method = VectorizeMethod::kPaper;
  const ValidationReport paper = ValidateOrDie(VectorizeOrDie(grid, options), grid);
  EXPECT_GT(paper.uncovered_points, 0);
  ExpectValid(VectorizeOrDie(grid), grid);
}

// Tiles --------------------------------------------------------------------------------------

struct TileRun {
  VectorMap whole;
  std::map<std::pair<int, int>, VectorMap> tiles;
};

TileRun VectorizeInTiles(const OccupancyGrid& grid, int tile, VectorizerOptions options = {}) {
  TileRun run;
  const Vectorizer vectorizer(options);
  for (int ty = 0; ty * tile < grid.height(); ++ty) {
    for (int tx = 0; tx * tile < grid.width(); ++tx) {
      const CellRect rect{tx * tile, ty * tile, std::min(tile, grid.width() - tx * tile),
                          std::min(tile, grid.height() - ty * tile)};
      auto map = vectorizer.VectorizeTile(grid, rect);
      EXPECT_TRUE(map.ok());
      run.tiles[{tx, ty}] = *map;
      run.whole.epsilon = map->epsilon;
      run.whole.resolution = map->resolution;
      run.whole.Append(*map);
    }
  }
  return run;
}

// Polyline end points of `map` lying on the line x = line (vertical) or y = line, cell units.
std::multiset<std::pair<double, double>> EndsOnLine(const VectorMap& map, const OccupancyGrid& grid,
                                                    bool vertical, double line) {
  const CellFrame frame(grid);
  std::multiset<std::pair<double, double>> ends;
  for (const Polyline& polyline : map.obstacles) {
    if (polyline.closed) continue;
    for (const Point2* p : {&polyline.points.front(), &polyline.points.back()}) {
      const Point2 c = frame.ToCell(*p);
      if (std::abs((vertical ? c.x() : c.y()) - line) < 1e-9) {
        ends.insert({p->x(), p->y()});  // map-frame coordinates, compared exactly
      }
    }
  }
  return ends;
}

OccupancyGrid SeamGrid() {
  OccupancyGrid grid(64, 64, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 2, 20, 61, 21, grid::kOccupiedValue);   // horizontal, 2 thick: crosses x borders
  FillRect(grid, 37, 2, 37, 61, grid::kOccupiedValue);   // vertical, 1 thick
  FillRect(grid, 10, 40, 28, 42, grid::kOccupiedValue);  // 3 thick across x = 16
  DrawLine(grid, 3, 57, 57, 3, 0.7);                     // diagonal (not through a corner)
  return grid;
}

TEST(VectorizerTileTest, TilesHoldConstraintsAndStitchWithoutSeams) {
  const OccupancyGrid grid = SeamGrid();
  const int tile = 16;
  const TileRun run = VectorizeInTiles(grid, tile);
  ExpectValid(run.whole, grid);
  for (const auto& [key, map] : run.tiles) {
    ValidatorOptions options;
    options.rect = CellRect{key.first * tile, key.second * tile, tile, tile};
    auto report = Validator(options).Validate(map, grid);
    ASSERT_TRUE(report.ok());
    EXPECT_TRUE(report->ok()) << "tile " << key.first << "," << key.second;
  }
  int shared_ends = 0;
  for (const auto& [key, map] : run.tiles) {
    const auto right = run.tiles.find({key.first + 1, key.second});
    if (right != run.tiles.end()) {
      const double line = (key.first + 1) * tile - 0.5;
      const auto mine = EndsOnLine(map, grid, true, line);
      EXPECT_EQ(mine, EndsOnLine(right->second, grid, true, line))
          << "border right of tile " << key.first << "," << key.second;
      shared_ends += static_cast<int>(mine.size());
    }
    const auto up = run.tiles.find({key.first, key.second + 1});
    if (up != run.tiles.end()) {
      const double line = (key.second + 1) * tile - 0.5;
      const auto mine = EndsOnLine(map, grid, false, line);
      EXPECT_EQ(mine, EndsOnLine(up->second, grid, false, line))
          << "border above tile " << key.first << "," << key.second;
      shared_ends += static_cast<int>(mine.size());
    }
  }
  EXPECT_GE(shared_ends, 8);
}

TEST(VectorizerTileTest, WallAlongATileBorderIsALineOnEachSide) {
  // A wall three cells thick lying on the border between two tiles, one or two of its rows on
  // each side, with or without pockets in its middle row: thinning cuts its skeleton into pieces
  // that hang on the anchors across the border. Each tile covers its rows with a line along the
  // wall, not with a fan of segments to border nodes (40 vertices over the four tiles before).
  for (const bool pockets : {false, true}) {
    for (const int left_rows : {1, 2}) {
      OccupancyGrid grid(40, 40, 0.05, {}, grid::kFreeValue);
      FillRect(grid, 20 - left_rows, 5, 22 - left_rows, 34, grid::kOccupiedValue);
      if (pockets) {
        for (int y = 7; y < 33; y += 4) grid.at(21 - left_rows, y) = grid::kUnknownValue;
      }
      const TileRun run = VectorizeInTiles(grid, 20);
      SCOPED_TRACE(::testing::Message()
                   << left_rows << " rows left of the border, pockets " << pockets);
      ExpectValid(run.whole, grid);
      size_t vertices = 0;
      for (const auto& [key, map] : run.tiles) vertices += map.ObstacleVertexCount();
      EXPECT_LE(vertices, 8u);  // a segment per tile, the wall being cut at y = 20 as well
    }
  }
}

TEST(VectorizerTileTest, QuantisedTilesStitchExactly) {
  const OccupancyGrid grid = SeamGrid();
  const int tile = 16;
  VectorizerOptions options;
  options.quantum = 0.8 / 16384;  // a quantum that does not divide half a cell (off the cells)
  options.lattice_origin = Point2(-0.4, 0.2);
  const TileRun run = VectorizeInTiles(grid, tile, options);
  ExpectValid(run.whole, grid);
  ExpectOnLattice(run.whole, options.quantum, options.lattice_origin);
  int shared_ends = 0;
  for (const auto& [key, map] : run.tiles) {
    const auto right = run.tiles.find({key.first + 1, key.second});
    if (right == run.tiles.end()) continue;
    // Snapped border nodes are no longer exactly on the border line: compare the ends nearest it.
    const double line = (key.first + 1) * tile - 0.5;
    auto near_line = [&](const VectorMap& m) {
      std::multiset<std::pair<double, double>> ends;
      const CellFrame frame(grid);
      for (const Polyline& polyline : m.obstacles) {
        if (polyline.closed) continue;
        for (const Point2* p : {&polyline.points.front(), &polyline.points.back()}) {
          if (std::abs(frame.ToCell(*p).x() - line) < 0.01) ends.insert({p->x(), p->y()});
        }
      }
      return ends;
    };
    const auto mine = near_line(map);
    EXPECT_EQ(mine, near_line(right->second));
    shared_ends += static_cast<int>(mine.size());
  }
  EXPECT_GE(shared_ends, 4);
}

TEST(VectorizerTileTest, ChangedTileIsRevectorizedAlone) {
  OccupancyGrid grid = SeamGrid();
  const int tile = 16;
  TileRun run = VectorizeInTiles(grid, tile);
  // Change the inside of tile (1, 1) only (not its border rows and columns).
  FillRect(grid, 19, 19, 28, 28, grid::kFreeValue);
  FillRect(grid, 20, 24, 27, 25, grid::kOccupiedValue);
  auto changed = Vectorizer().VectorizeTile(grid, CellRect{16, 16, 16, 16});
  ASSERT_TRUE(changed.ok());
  VectorMap merged;
  merged.epsilon = run.whole.epsilon;
  merged.resolution = run.whole.resolution;
  for (auto& [key, map] : run.tiles) {
    if (key == std::make_pair(1, 1)) map = *changed;
    merged.Append(map);
  }
  ExpectValid(merged, grid);
}

// Solid blocks cut by tile borders, one ending exactly on a border and one starting on it: each
// tile outlines its part, and no occupied cell comes back free, also after a tile is re-vectorized.
TEST(VectorizerTileTest, SolidBlocksAtTileBordersComeBackWithoutFreeCells) {
  OccupancyGrid grid(80, 64, 0.05, {}, grid::kFreeValue);
  FillRect(grid, 10, 10, 35, 29, grid::kOccupiedValue);  // across x = 16 and x = 32, y = 16
  FillRect(grid, 40, 36, 47, 55, grid::kOccupiedValue);  // ends on the border x = 48
  FillRect(grid, 48, 5, 63, 20, grid::kOccupiedValue);   // fills tile (3, 0) from x = 48
  TiledVectorizeOptions options;
  options.tile_size = 0.8;  // 16 cells
  TiledVectorMap tiled = *VectorizeTiled(grid, Transform2::Identity(), options);
  auto round_trip = [&] { return *Rasterizer().Rasterize(tiled.Merged(), grid); };
  EXPECT_EQ(testing::OccupiedComeBackFree(grid, round_trip()), 0);
  ExpectValid(tiled.Merged(), grid);

  // A block against the border x = 32 inside tile (1, 3) and the neighbour it reaches into.
  FillRect(grid, 24, 50, 31, 60, grid::kOccupiedValue);
  FillRect(grid, 32, 52, 35, 58, grid::kOccupiedValue);
  for (const TileId tile : {TileId{1, 3}, TileId{2, 3}}) {
    ASSERT_TRUE(RevectorizeTile(grid, Transform2::Identity(), tile, options, &tiled).ok());
  }
  EXPECT_EQ(testing::OccupiedComeBackFree(grid, round_trip()), 0);
  ExpectValid(tiled.Merged(), grid);
  // Re-vectorizing tiles gives what vectorizing the changed grid gives.
  const TiledVectorMap fresh = *VectorizeTiled(grid, Transform2::Identity(), options);
  ASSERT_EQ(tiled.tiles.size(), fresh.tiles.size());
  for (const auto& [id, tile] : fresh.tiles) {
    ASSERT_TRUE(tiled.tiles.count(id)) << id;
    EXPECT_EQ(tiled.tiles.at(id).obstacles, tile.obstacles) << id;
    EXPECT_EQ(tiled.tiles.at(id).free_space, tile.free_space) << id;
  }
}

}  // namespace
}  // namespace fleetmap::vector_map
