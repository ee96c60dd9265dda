#include "bench/bytes/tile_bytes_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace fleetmap::bench {
namespace {

using ::testing::HasSubstr;

TileBytesComparison Comparison(size_t vector, size_t zstd19, size_t tiles) {
  TileBytesComparison comparison;
  comparison.grid.tiles = tiles;
  comparison.grid.bytes = {
      .raw = 4096, .patch_cdr = 4136, .zstd3 = 3072, .zstd19 = zstd19, .lz4 = 3500};
  comparison.vector.tiles = tiles;
  comparison.vector.payload = vector;
  return comparison;
}

TEST(TileBytesTableTest, EveryRatioColumnNamesItsBaseline) {
  std::ostringstream out;
  PrintTileBytesTable({{"lab", Comparison(1024, 2048, 2)}}, "map", out);
  const std::string table = out.str();
  EXPECT_THAT(table,
              HasSubstr("| map | tiles | grid patch CDR KB | grid zstd -3 KB | grid zstd -19 "
                        "KB | grid LZ4 KB | vector tiles KB | vector / patch CDR | vector "
                        "/ zstd -3 | vector / zstd -19 | vector / LZ4 | vector / smallest "
                        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n"));
  EXPECT_THAT(table, HasSubstr("| lab | 2 | 4.0 | 3.0 | 2.0 | 3.4 | 1.0 | 0.25 | 0.33 | 0.50 | "
                               "0.29 | 0.50 (zstd -19) |\n"));
  EXPECT_THAT(table, HasSubstr("| **sum** | 2 |"));
  EXPECT_THAT(table, HasSubstr("Vector tiles / smallest baseline: **0.50** summed (vs zstd -19); "
                               "worst map **0.50** (lab, vs zstd -19)."));
}

TEST(TileBytesTableTest, SaysWhenTheTwoSidesSentDifferentTiles) {
  TileBytesComparison comparison = Comparison(1024, 2048, 3);
  comparison.vector.tiles = 2;
  std::ostringstream out;
  PrintTileBytesTable({{"lab", comparison}}, "terrain", out);
  EXPECT_THAT(out.str(), HasSubstr("| lab | grid 3 / vector 2 |"));
  EXPECT_THAT(out.str(), HasSubstr("worst terrain"));
}

TEST(TileBytesTableTest, CsvHasAFieldPerColumn) {
  const std::string header = TileBytesCsvHeader();
  const std::vector<std::string> fields = TileBytesCsvFields(Comparison(1024, 2048, 2));
  EXPECT_EQ(static_cast<size_t>(std::count(header.begin(), header.end(), ',')) + 1, fields.size());
  EXPECT_EQ(fields.front(), "2");
  EXPECT_EQ(fields[fields.size() - 2], "zstd -19");
  EXPECT_EQ(fields.back(), "0.5000");
}

TEST(TileBytesTableTest, TheDictionaryColumnAppearsWhenARowHasItAndOthersShowADash) {
  TileBytesComparison with = Comparison(1024, 2048, 2);
  with.grid.bytes.zstd19_dict = 4096;
  std::ostringstream out;
  PrintTileBytesTable({{"lab", with}, {"house", Comparison(512, 1024, 1)}}, "map", out);
  const std::string table = out.str();
  EXPECT_THAT(table, HasSubstr("| grid zstd -19 + dictionary KB | vector tiles KB |"));
  EXPECT_THAT(table, HasSubstr("| vector / zstd -19 + dictionary | vector / smallest |"));
  EXPECT_THAT(table, HasSubstr("| lab | 2 | 4.0 | 3.0 | 2.0 | 3.4 | 4.0 | 1.0 |"));
  EXPECT_THAT(table, HasSubstr("| house | 1 | 4.0 | 3.0 | 1.0 | 3.4 | - | 0.5 |"));
  // The CSV keeps its columns either way; the ratio to an unmeasured baseline stays empty.
  const std::vector<std::string> fields = TileBytesCsvFields(Comparison(1024, 2048, 2));
  EXPECT_EQ(fields[7], "0");
  EXPECT_EQ(fields[fields.size() - 3], "");
  const std::vector<std::string> with_fields = TileBytesCsvFields(with);
  EXPECT_EQ(with_fields[7], "4096");
  EXPECT_EQ(with_fields[with_fields.size() - 3], "0.2500");
}

}  // namespace
}  // namespace fleetmap::bench
