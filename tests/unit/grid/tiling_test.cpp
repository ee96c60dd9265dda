#include "common/grid/tiling.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "common/grid/map_io.hpp"

namespace fleetmap::grid {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

Transform2 Translation(double x, double y) {
  Transform2 transform = Transform2::Identity();
  transform.translate(Point2(x, y));
  return transform;
}

OccupancyGrid RandomGrid(std::mt19937& rng, int width, int height, double resolution,
                         Pose2 origin) {
  OccupancyGrid grid(width, height, resolution, origin);
  std::uniform_int_distribution<int> value(-1, 100);
  for (int8_t& cell : grid.mutable_data()) cell = static_cast<int8_t>(value(rng));
  return grid;
}

std::vector<TileId> Keys(const TileGrids& tiles) {
  std::vector<TileId> keys;
  for (const auto& [id, tile] : tiles) keys.push_back(id);
  return keys;
}

// Split, then stitch into an unknown grid of the same geometry: must give the input back, and
// every cell must have gone to the tile containing its centre.
void ExpectExactSplitStitch(const OccupancyGrid& grid, const Transform2& fleet_from_map,
                            double tile_size) {
  SCOPED_TRACE(::testing::Message()
               << grid.width() << " x " << grid.height() << " @ " << grid.resolution() << " origin "
               << grid.origin() << " tile " << tile_size);
  TilingOptions options;
  options.tile_size = tile_size;
  const StatusOr<TileGrids> tiles = SplitIntoTiles(grid, fleet_from_map, options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  OccupancyGrid stitched(grid.width(), grid.height(), grid.resolution(), grid.origin());
  ASSERT_TRUE(StitchTiles(*tiles, fleet_from_map, &stitched).ok());
  EXPECT_TRUE(stitched == grid);
  // Membership: each tile's cell centres lie in the tile's square (up to rounding of the centre).
  const double slack = 1e-9 * std::max(1.0, tile_size);
  int64_t known_cells = 0;
  for (const auto& [id, tile] : *tiles) {
    EXPECT_EQ(tile.resolution(), grid.resolution());
    EXPECT_EQ(tile.origin().yaw, 0.0);
    for (const int corner_x : {0, tile.width() - 1}) {
      for (const int corner_y : {0, tile.height() - 1}) {
        const Point2 centre = tile.CellCenter(corner_x, corner_y);
        EXPECT_GE(centre.x(), id.x * tile_size - slack) << id;
        EXPECT_LT(centre.x(), (id.x + 1) * tile_size + slack) << id;
        EXPECT_GE(centre.y(), id.y * tile_size - slack) << id;
        EXPECT_LT(centre.y(), (id.y + 1) * tile_size + slack) << id;
      }
    }
    for (const int8_t v : tile.data()) known_cells += v != kUnknownValue;
  }
  int64_t expected_known = 0;
  for (const int8_t v : grid.data()) expected_known += v != kUnknownValue;
  EXPECT_EQ(known_cells, expected_known);
}

TEST(TilingTest, AssignsCellsToTheTileHoldingTheirCentre) {
  OccupancyGrid grid(10, 3, 1.0, Pose2{}, kFreeValue);
  TilingOptions options;
  options.tile_size = 4.0;
  const StatusOr<TileGrids> tiles = SplitIntoTiles(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  EXPECT_EQ(Keys(*tiles), (std::vector<TileId>{{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(tiles->at({0, 0}).width(), 4);
  EXPECT_EQ(tiles->at({1, 0}).width(), 4);
  EXPECT_EQ(tiles->at({2, 0}).width(), 2);
  EXPECT_EQ(tiles->at({2, 0}).height(), 3);
  EXPECT_EQ(tiles->at({1, 0}).origin(), (Pose2{4.0, 0.0, 0.0}));
}

TEST(TilingTest, NegativeCoordinatesFloorDownward) {
  // Cells of 0.5 m from x = -2.5: centres -2.25, -1.75, ..., tiles of 1 m.
  OccupancyGrid grid(6, 1, 0.5, Pose2{-2.5, -0.5, 0.0}, kFreeValue);
  TilingOptions options;
  options.tile_size = 1.0;
  const StatusOr<TileGrids> tiles = SplitIntoTiles(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  // Centres -2.25 -> -3; -1.75, -1.25 -> -2; -0.75, -0.25 -> -1; 0.25 -> 0. Row centre -0.25 -> -1.
  EXPECT_EQ(Keys(*tiles), (std::vector<TileId>{{-3, -1}, {-2, -1}, {-1, -1}, {0, -1}}));
  EXPECT_EQ(tiles->at({-3, -1}).width(), 1);
  EXPECT_EQ(tiles->at({-2, -1}).width(), 2);
  EXPECT_EQ(tiles->at({0, -1}).origin(), (Pose2{0.0, -0.5, 0.0}));
}

TEST(TilingTest, TranslationMovesCellsInTheFleetFrame) {
  OccupancyGrid grid(4, 4, 1.0, Pose2{}, kFreeValue);
  TilingOptions options;
  options.tile_size = 2.0;
  const StatusOr<TileGrids> tiles = SplitIntoTiles(grid, Translation(100.0, -1.0), options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  // x centres 100.5..103.5 -> tiles 50, 51; y centres -0.5..2.5 -> tiles -1 (1 row), 0, 1 (1 row).
  EXPECT_EQ(Keys(*tiles),
            (std::vector<TileId>{{50, -1}, {50, 0}, {50, 1}, {51, -1}, {51, 0}, {51, 1}}));
  EXPECT_EQ(tiles->at({50, -1}).height(), 1);
  EXPECT_EQ(tiles->at({50, 0}).height(), 2);
  EXPECT_EQ(tiles->at({51, 1}).origin(), (Pose2{102.0, 2.0, 0.0}));
}

TEST(TilingTest, SkipsAllUnknownTilesUnlessAsked) {
  OccupancyGrid grid(4, 2, 1.0, Pose2{});  // all unknown
  grid.at(3, 1) = 42;
  TilingOptions options;
  options.tile_size = 2.0;
  StatusOr<TileGrids> tiles = SplitIntoTiles(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  EXPECT_EQ(Keys(*tiles), (std::vector<TileId>{{1, 0}}));
  options.skip_unknown_tiles = false;
  tiles = SplitIntoTiles(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  EXPECT_EQ(tiles->size(), 2u);
}

TEST(TilingTest, CellRectsPartitionTheGridLikeSplit) {
  OccupancyGrid grid(37, 23, 0.1, Pose2{-1.05, 0.3, 0.0}, kFreeValue);
  const Transform2 fleet_from_map = Pose2{0.25, -0.5, 0.0}.ToTransform();
  const auto rects = TileCellRects(grid, fleet_from_map, 1.0);
  ASSERT_TRUE(rects.ok()) << rects.status();
  const auto tiles = SplitIntoTiles(grid, fleet_from_map, {.tile_size = 1.0});
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  ASSERT_EQ(rects->size(), tiles->size());
  std::vector<int> covered(static_cast<size_t>(grid.cell_count()), 0);
  for (const auto& [id, rect] : *rects) {
    const OccupancyGrid& tile = tiles->at(id);
    EXPECT_EQ(rect.width, tile.width()) << id;
    EXPECT_EQ(rect.height, tile.height()) << id;
    // The tile's first cell is the rectangle's first cell, in the fleet frame.
    const Point2 first = fleet_from_map * grid.CellCenter(rect.x0, rect.y0);
    EXPECT_NEAR(first.x(), tile.CellCenter(0, 0).x(), 1e-9) << id;
    EXPECT_NEAR(first.y(), tile.CellCenter(0, 0).y(), 1e-9) << id;
    for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
      for (int x = rect.x0; x < rect.x0 + rect.width; ++x) ++covered[y * grid.width() + x];
    }
  }
  EXPECT_THAT(covered, ::testing::Each(1));
}

TEST(TilingTest, RejectsRotationAndBadTileSize) {
  const OccupancyGrid grid(4, 4, 1.0, Pose2{});
  Transform2 rotated = Transform2::Identity();
  rotated.rotate(0.1);
  EXPECT_THAT(SplitIntoTiles(grid, rotated).status().message(),
              HasSubstr("tiling needs a pure translation"));
  const OccupancyGrid yawed(4, 4, 1.0, Pose2{0.0, 0.0, std::numbers::pi / 2});
  EXPECT_THAT(SplitIntoTiles(yawed, Transform2::Identity()).status().message(),
              HasSubstr("origin yaw"));
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    TilingOptions options;
    options.tile_size = bad;
    const Status status = SplitIntoTiles(grid, Transform2::Identity(), options).status();
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_THAT(status.message(), HasSubstr("tile_size")) << bad;
  }
  EXPECT_THAT(SplitIntoTiles(grid, Translation(3e12, 0.0), {.tile_size = 1e-3}).status().message(),
              HasSubstr("out of the int32 range"));
  const StatusOr<TileGrids> empty = SplitIntoTiles(OccupancyGrid(), Transform2::Identity());
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->empty());
}

TEST(TilingTest, SplitStitchIsExactOnOddSizesOffsetsAndTileSizes) {
  std::mt19937 rng(42);
  struct Geometry {
    int width;
    int height;
    double resolution;
    Pose2 origin;
  };
  const std::vector<Geometry> geometries = {{1, 1, 0.05, {0.0, 0.0, 0.0}},
                                            {7, 13, 0.05, {-15.1, -25.0, 0.0}},
                                            {33, 5, 0.1, {0.013, -7.77, 0.0}},
                                            {64, 64, 0.03, {-0.015, 0.045, 0.0}},
                                            {17, 29, 0.07, {-3.5, 2.1, 0.0}},
                                            {50, 3, 0.3, {-1e3, 1e3, 0.0}},
                                            {21, 21, 1.0 / 3.0, {-7.0 / 3, 0.0, 0.0}}};
  const std::vector<double> tile_sizes = {1.0, 0.35, 2.5, 0.05, 0.01, 0.21, 10.0, 1.0 / 3.0};
  const std::vector<Transform2> transforms = {Transform2::Identity(), Translation(0.3, -1.1),
                                              Translation(-12.345, 987.6)};
  for (const Geometry& g : geometries) {
    const OccupancyGrid grid = RandomGrid(rng, g.width, g.height, g.resolution, g.origin);
    for (const double tile_size : tile_sizes) {
      for (const Transform2& transform : transforms) {
        ExpectExactSplitStitch(grid, transform, tile_size);
      }
    }
  }
}

TEST(TilingTest, SplitStitchIsExactOnEverySharedMap) {
  const fs::path maps_dir(FLEETMAP_SHARED_MAPS_DIR);
  if (!fs::is_directory(maps_dir)) GTEST_SKIP() << "no shared maps at " << maps_dir;
  int maps = 0;
  for (const auto& entry : fs::directory_iterator(maps_dir)) {
    if (entry.path().extension() != ".yaml") continue;
    const StatusOr<LoadedMap> map = LoadMap(entry.path().string());
    ASSERT_TRUE(map.ok()) << map.status();
    ExpectExactSplitStitch(map->grid, Transform2::Identity(), 5.0);
    ExpectExactSplitStitch(map->grid, Translation(0.3, -1.1), 3.7);
    ++maps;
  }
  EXPECT_GT(maps, 0);
}

TEST(TilingTest, StitchWithoutTargetRebuildsTheGridInTheFleetFrame) {
  std::mt19937 rng(3);
  OccupancyGrid grid = RandomGrid(rng, 23, 11, 0.05, Pose2{-1.23, 4.56, 0.0});
  for (int8_t& cell : grid.mutable_data()) cell = cell < 0 ? 0 : cell;  // no skipped tiles
  const Transform2 fleet_from_map = Translation(2.0, -3.0);
  const StatusOr<TileGrids> tiles = SplitIntoTiles(grid, fleet_from_map, {.tile_size = 0.3});
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  const StatusOr<OccupancyGrid> stitched = StitchTiles(*tiles);
  ASSERT_TRUE(stitched.ok()) << stitched.status();
  EXPECT_EQ(stitched->width(), grid.width());
  EXPECT_EQ(stitched->height(), grid.height());
  EXPECT_EQ(stitched->origin(), (Pose2{-1.23 + 2.0, 4.56 - 3.0, 0.0}));
  EXPECT_TRUE(stitched->data() == grid.data());
  const StatusOr<OccupancyGrid> none = StitchTiles(TileGrids{});
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

TEST(TilingTest, StitchRejectsTilesThatDoNotFitAndLeavesTargetUnchanged) {
  const OccupancyGrid source(8, 8, 0.5, Pose2{}, kFreeValue);
  const StatusOr<TileGrids> tiles =
      SplitIntoTiles(source, Transform2::Identity(), {.tile_size = 2.0});
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  const OccupancyGrid pristine(8, 8, 0.5, Pose2{});

  TileGrids misaligned = *tiles;
  misaligned.at({1, 1}) = OccupancyGrid(4, 4, 0.5, Pose2{2.1, 2.0, 0.0}, kOccupiedValue);
  OccupancyGrid target = pristine;
  EXPECT_THAT(StitchTiles(misaligned, Transform2::Identity(), &target).message(),
              HasSubstr("tile(1, 1): origin is not on the target grid's cell lattice"));
  EXPECT_TRUE(target == pristine);

  TileGrids coarse = *tiles;
  coarse.at({0, 0}) = OccupancyGrid(2, 2, 1.0, Pose2{}, kOccupiedValue);
  EXPECT_THAT(StitchTiles(coarse, Transform2::Identity(), &target).message(),
              HasSubstr("tile(0, 0): resolution"));

  OccupancyGrid small(4, 4, 0.5, Pose2{});
  EXPECT_THAT(StitchTiles(*tiles, Transform2::Identity(), &small).message(),
              HasSubstr("outside the target's 4 x 4 cells"));
  EXPECT_TRUE(small == OccupancyGrid(4, 4, 0.5, Pose2{}));

  TileGrids mixed = *tiles;
  mixed.at({1, 0}) = OccupancyGrid(4, 4, 0.25, Pose2{2.0, 0.0, 0.0});
  EXPECT_FALSE(StitchTiles(mixed).ok());
}

}  // namespace
}  // namespace fleetmap::grid
