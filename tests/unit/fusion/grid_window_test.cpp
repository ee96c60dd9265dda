#include "common/fusion/grid_window.hpp"

#include <gtest/gtest.h>

#include <climits>

namespace fleetmap::fusion {
namespace {

// Tiles all mapped by one robot, in this order.
std::vector<SourcedTile> ByOneRobot(const std::vector<TileId>& tiles, int robot = 0) {
  std::vector<SourcedTile> sourced;
  for (const TileId& tile : tiles) sourced.push_back({tile, {robot}, sourced.size()});
  return sourced;
}

TEST(GridWindowTest, TilesThatFitAreAllShown) {
  const GridWindow window = ChooseGridWindow(ByOneRobot({{0, 0}, {3, 1}, {-2, 5}}), 100);
  EXPECT_EQ(window.rect.min, (TileId{-2, 0}));
  EXPECT_EQ(window.rect.max, (TileId{3, 5}));
  EXPECT_EQ(window.tiles_shown, 3u);
  EXPECT_EQ(window.tiles_left_out, 0u);
}

TEST(GridWindowTest, AFarTileIsLeftOutAndTheFirstGroupShown) {
  // A 3 x 3 block at the origin and one tile at the far end of the int32 range.
  std::vector<TileId> tiles;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) tiles.push_back({x, y});
  }
  tiles.push_back({INT32_MAX, INT32_MAX});
  const GridWindow window = ChooseGridWindow(ByOneRobot(tiles), 1000);
  EXPECT_EQ(window.rect.min, (TileId{0, 0}));
  EXPECT_EQ(window.rect.max, (TileId{2, 2}));
  EXPECT_EQ(window.tiles_shown, 9u);
  EXPECT_EQ(window.tiles_left_out, 1u);
}

TEST(GridWindowTest, TilesAFewEmptyTilesApartAreOneGroup) {
  // Two rooms two empty tiles apart, and a lone tile 100 tiles away (mapped last).
  const std::vector<TileId> tiles = {{0, 0}, {1, 0}, {4, 0}, {5, 1}, {100, 100}};
  const GridWindow window = ChooseGridWindow(ByOneRobot(tiles), 50);
  EXPECT_EQ(window.rect.min, (TileId{0, 0}));
  EXPECT_EQ(window.rect.max, (TileId{5, 1}));
  EXPECT_EQ(window.tiles_left_out, 1u);
}

TEST(GridWindowTest, AGroupLargerThanTheBudgetIsCutAroundItsMedian) {
  std::vector<TileId> tiles;
  for (int x = 0; x < 100; ++x) tiles.push_back({x, 7});              // one long corridor
  const GridWindow window = ChooseGridWindow(ByOneRobot(tiles), 25);  // at most 5 x 5 tiles
  EXPECT_LE(window.rect.area(), 25);
  EXPECT_TRUE(window.rect.Contains({50, 7}));
  EXPECT_EQ(window.tiles_shown + window.tiles_left_out, 100u);
  EXPECT_EQ(window.tiles_shown, static_cast<size_t>(window.rect.width()));
}

TEST(GridWindowTest, ThousandsOfScatteredTilesCostTheirCountNotTheirSpan) {
  // 2000 tiles 1 km apart (tile keys 100 apart): a bounding box of 4e10 tiles.
  std::vector<TileId> tiles;
  for (int i = 0; i < 2000; ++i) tiles.push_back({(i % 45) * 100, (i / 45) * 100});
  const GridWindow window = ChooseGridWindow(ByOneRobot(tiles), 1 << 16);
  EXPECT_EQ(window.rect.area(), 1);
  EXPECT_EQ(window.tiles_shown, 1u);
  EXPECT_EQ(window.tiles_left_out, 1999u);
}

TEST(GridWindowTest, OneRobotsFarTilesCannotTakeTheViewFromTheFleet) {
  // Two robots share three tiles at the origin; a third robot holds 50 tiles 10 km away.
  std::vector<SourcedTile> tiles = {{{0, 0}, {0, 1}, 1}, {{1, 0}, {0}, 2}, {{1, 1}, {1}, 3}};
  for (int i = 0; i < 50; ++i) tiles.push_back({{1000 + i % 10, i / 10}, {2}, 4u + i});
  const GridWindow window = ChooseGridWindow(tiles, 400);
  EXPECT_EQ(window.rect.min, (TileId{0, 0}));
  EXPECT_EQ(window.rect.max, (TileId{1, 1}));
  EXPECT_EQ(window.tiles_left_out, 50u);
}

TEST(GridWindowTest, ALaterRobotsManyFarTilesCannotTakeTheViewFromTheFirst) {
  // One robot maps three tiles; a second, later, sends 1000 tiles 10 km away.
  std::vector<SourcedTile> tiles = {{{0, 0}, {0}, 1}, {{1, 0}, {0}, 2}, {{0, 1}, {0}, 3}};
  for (int i = 0; i < 1000; ++i) tiles.push_back({{1000 + i % 40, i / 40}, {1}, 4u + i});
  const GridWindow window = ChooseGridWindow(tiles, 400);
  EXPECT_EQ(window.rect.min, (TileId{0, 0}));
  EXPECT_EQ(window.rect.max, (TileId{1, 1}));
  EXPECT_EQ(window.tiles_left_out, 1000u);
}

TEST(GridWindowTest, DozensOfIdsMappingFarAwayLaterCannotTakeTheViewFromTheFleet) {
  // Four robots map four tiles; later a peer claiming 64 robot ids sends 64 tiles 13 km away.
  std::vector<SourcedTile> tiles = {
      {{0, 0}, {0, 1}, 1}, {{1, 0}, {1, 2}, 2}, {{0, 1}, {2, 3}, 3}, {{1, 1}, {3}, 4}};
  for (int i = 0; i < 64; ++i) tiles.push_back({{1300 + i % 16, i / 16}, {4 + i}, 5u + i});
  const GridWindow window = ChooseGridWindow(tiles, 400);
  EXPECT_EQ(window.rect.min, (TileId{0, 0}));
  EXPECT_EQ(window.rect.max, (TileId{1, 1}));
  EXPECT_EQ(window.tiles_left_out, 64u);
}

}  // namespace
}  // namespace fleetmap::fusion
