#include "bench/bytes/grid_tile_bytes.hpp"

#include <gtest/gtest.h>

#include "common/grid/tiling.hpp"

namespace fleetmap::bench {
namespace {

// map_msgs/OccupancyGridUpdate with frame "map" before its cells: encapsulation 4, stamp 8,
// frame_id 4 + 4, x y width height 16, data length 4.
constexpr size_t kPatchHeaderBytes = 40;

// 20 m x 10 m at 0.05 m: the fleet tiles (0, 0) and (1, 0), 200 x 200 cells each. Tile (0, 0)
// holds a free room with walls; tile (1, 0) is left unknown.
grid::OccupancyGrid RoomAndUnknown() {
  grid::OccupancyGrid grid(400, 200, 0.05);
  for (int y = 20; y < 180; ++y) {
    for (int x = 20; x < 180; ++x) {
      const bool wall = x == 20 || x == 179 || y == 20 || y == 179;
      grid.at(x, y) = wall ? grid::kOccupiedValue : grid::kFreeValue;
    }
  }
  return grid;
}

TEST(GridTileBytesTest, AnAllUnknownTileCompressesToAFewBytes) {
  const grid::OccupancyGrid grid(200, 200, 0.05);  // unknown everywhere
  const StatusOr<GridTileBytes> bytes = MeasureGridTileBytes(grid, {0, 0, 200, 200});
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  EXPECT_EQ(bytes->raw, 40000u);
  EXPECT_EQ(bytes->patch_cdr, kPatchHeaderBytes + 40000u);
  EXPECT_LT(bytes->zstd3, 32u);
  EXPECT_LT(bytes->zstd19, 32u);
  // LZ4 spends a byte per 255 bytes of a long match: still a hundredth of the cells.
  EXPECT_LT(bytes->lz4, 400u);
}

TEST(GridTileBytesTest, PatchIsTheCellsOfTheRectangleBehindTheCdrHeader) {
  const grid::OccupancyGrid grid = RoomAndUnknown();
  const StatusOr<GridTileBytes> bytes = MeasureGridTileBytes(grid, {15, 10, 7, 5});
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  EXPECT_EQ(bytes->raw, 35u);
  EXPECT_EQ(bytes->patch_cdr, kPatchHeaderBytes + 35u);
}

TEST(GridTileBytesTest, NamesTheBaselinesAndFindsTheSmallest) {
  GridTileBytes bytes;
  bytes.raw = 40000;
  bytes.patch_cdr = 40040;
  bytes.zstd3 = 900;
  bytes.zstd19 = 700;
  bytes.lz4 = 1500;
  const std::vector<NamedBytes> baselines = TileBaselines(bytes);
  ASSERT_EQ(baselines.size(), 4u);
  EXPECT_EQ(baselines[0].name, "patch CDR");
  EXPECT_EQ(baselines[1].name, "zstd -3");
  EXPECT_EQ(baselines[2].name, "zstd -19");
  EXPECT_EQ(baselines[3].name, "LZ4");
  EXPECT_EQ(SmallestTileBaseline(bytes).name, "zstd -19");
  EXPECT_EQ(SmallestTileBaseline(bytes).bytes, 700u);
  bytes.lz4 = 500;
  EXPECT_EQ(SmallestTileBaseline(bytes).name, "LZ4");
}

TEST(GridTileBytesTest, TheDictionaryBaselineIsNamedOnlyWhenMeasured) {
  GridTileBytes bytes;
  bytes.patch_cdr = 40040;
  bytes.zstd3 = 900;
  bytes.zstd19 = 700;
  bytes.lz4 = 1500;
  ASSERT_EQ(TileBaselines(bytes).size(), 4u);
  bytes.zstd19_dict = 650;
  const std::vector<NamedBytes> baselines = TileBaselines(bytes);
  ASSERT_EQ(baselines.size(), 5u);
  EXPECT_EQ(baselines[4].name, "zstd -19 + dictionary");
  EXPECT_EQ(SmallestTileBaseline(bytes).name, "zstd -19 + dictionary");
  bytes.zstd19_dict = 750;  // a dictionary can also cost more than none
  EXPECT_EQ(SmallestTileBaseline(bytes).name, "zstd -19");
}

TEST(GridTileBytesTest, SamplesAreTheCountedTilesCellsAndFeedTheDictionaryBaseline) {
  const grid::OccupancyGrid grid = RoomAndUnknown();
  const StatusOr<std::vector<std::vector<uint8_t>>> samples =
      GridTileSamples(grid, Transform2::Identity(), 10.0);
  ASSERT_TRUE(samples.ok()) << samples.status();
  const StatusOr<TiledGridBytes> plain = MeasureTiledGridBytes(grid, Transform2::Identity(), 10.0);
  ASSERT_TRUE(plain.ok()) << plain.status();
  ASSERT_EQ(samples->size(), plain->tiles);
  for (const std::vector<uint8_t>& sample : *samples) EXPECT_EQ(sample.size(), 200u * 200u);

  // Trained on eight copies of the map's tiles, the dictionary knows them: each tile costs less.
  std::vector<std::vector<uint8_t>> training;
  for (int copy = 0; copy < 8; ++copy) {
    training.insert(training.end(), samples->begin(), samples->end());
  }
  const StatusOr<ZstdDictionary> dictionary = ZstdDictionary::Train(training);
  ASSERT_TRUE(dictionary.ok()) << dictionary.status();
  const StatusOr<TiledGridBytes> with =
      MeasureTiledGridBytes(grid, Transform2::Identity(), 10.0, &*dictionary);
  ASSERT_TRUE(with.ok()) << with.status();
  EXPECT_GT(with->bytes.zstd19_dict, 0u);
  EXPECT_LT(with->bytes.zstd19_dict, with->bytes.zstd19);
  EXPECT_EQ(with->bytes.zstd19, plain->bytes.zstd19);  // the other baselines are unchanged
  EXPECT_EQ(plain->bytes.zstd19_dict, 0u);             // not measured without a dictionary
}

TEST(GridTileBytesTest, SumsTheKnownTilesOfAMapEachCompressedAlone) {
  const grid::OccupancyGrid grid = RoomAndUnknown();
  const StatusOr<TiledGridBytes> tiled = MeasureTiledGridBytes(grid, Transform2::Identity(), 10.0);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  // Tile (1, 0) is all unknown: the vector wire sends nothing for it, nor does the baseline.
  EXPECT_EQ(tiled->tiles, 1u);
  const StatusOr<GridTileBytes> room = MeasureGridTileBytes(grid, {0, 0, 200, 200});
  ASSERT_TRUE(room.ok());
  EXPECT_EQ(tiled->bytes.raw, room->raw);
  EXPECT_EQ(tiled->bytes.patch_cdr, room->patch_cdr);
  EXPECT_EQ(tiled->bytes.zstd3, room->zstd3);
  EXPECT_EQ(tiled->bytes.zstd19, room->zstd19);
  EXPECT_EQ(tiled->bytes.lz4, room->lz4);
}

TEST(GridTileBytesTest, CutsAShiftedMapIntoTheFleetTilesItTouches) {
  // Half a tile to the right in the fleet frame: cells 0-99 fall in fleet tile (0, 0), 100-299
  // in (1, 0), 300-399 in (2, 0). The room spans the first two, so two patches carry it, each
  // with its own header and compressed alone; (2, 0) holds only unknown cells.
  const grid::OccupancyGrid grid = RoomAndUnknown();
  Transform2 fleet_from_map = Transform2::Identity();
  fleet_from_map.translation() = Eigen::Vector2d(5.0, 0.0);
  const StatusOr<TiledGridBytes> tiled = MeasureTiledGridBytes(grid, fleet_from_map, 10.0);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  EXPECT_EQ(tiled->tiles, 2u);
  EXPECT_EQ(tiled->bytes.raw, 100u * 200 + 200u * 200);
  EXPECT_EQ(tiled->bytes.patch_cdr, tiled->bytes.raw + 2 * kPatchHeaderBytes);
}

TEST(GridTileBytesTest, RefusesATileSizeTheTilingRefuses) {
  EXPECT_FALSE(MeasureTiledGridBytes(RoomAndUnknown(), Transform2::Identity(), 0.0).ok());
}

}  // namespace
}  // namespace fleetmap::bench
