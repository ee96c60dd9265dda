#include "bench/bytes/tile_bytes_comparison.hpp"

#include <gtest/gtest.h>

namespace fleetmap::bench {
namespace {

// `tiles` tiles whose grid baselines are patch 10 000, zstd -3 `zstd3`, zstd -19 `zstd19`,
// LZ4 2 000 bytes, and whose vector tiles are `vector` bytes.
TileBytesComparison Comparison(size_t vector, size_t zstd3, size_t zstd19, size_t tiles = 1) {
  TileBytesComparison comparison;
  comparison.grid.tiles = tiles;
  comparison.grid.bytes.raw = 9960;
  comparison.grid.bytes.patch_cdr = 10000;
  comparison.grid.bytes.zstd3 = zstd3;
  comparison.grid.bytes.zstd19 = zstd19;
  comparison.grid.bytes.lz4 = 2000;
  comparison.vector.tiles = tiles;
  comparison.vector.payload = vector;
  return comparison;
}

TEST(TileBytesComparisonTest, RatiosNameEachBaselineInReportOrder) {
  const std::vector<NamedRatio> ratios = Comparison(500, 1250, 1000).Ratios();
  ASSERT_EQ(ratios.size(), 4u);
  EXPECT_EQ(ratios[0].baseline, "patch CDR");
  EXPECT_DOUBLE_EQ(ratios[0].ratio, 0.05);
  EXPECT_EQ(ratios[1].baseline, "zstd -3");
  EXPECT_DOUBLE_EQ(ratios[1].ratio, 0.4);
  EXPECT_EQ(ratios[2].baseline, "zstd -19");
  EXPECT_DOUBLE_EQ(ratios[2].ratio, 0.5);
  EXPECT_EQ(ratios[3].baseline, "LZ4");
  EXPECT_DOUBLE_EQ(ratios[3].ratio, 0.25);
  EXPECT_EQ(TileBaselineNames(),
            (std::vector<std::string>{"patch CDR", "zstd -3", "zstd -19", "LZ4"}));
}

TEST(TileBytesComparisonTest, ComparesWithTheSmallestBaseline) {
  const TileBytesComparison comparison = Comparison(500, 1250, 1000);
  EXPECT_EQ(comparison.RatioToSmallest().baseline, "zstd -19");
  EXPECT_DOUBLE_EQ(comparison.RatioToSmallest().ratio, 0.5);
  EXPECT_DOUBLE_EQ(comparison.RatioTo(&GridTileBytes::zstd3), 0.4);
}

TEST(TileBytesComparisonTest, NoBaselineBytesGiveARatioOfZero) {
  EXPECT_DOUBLE_EQ(TileBytesComparison{}.RatioToSmallest().ratio, 0.0);
}

TEST(TileBytesComparisonTest, HeadlineSumsTheMapsAndNamesTheWorst) {
  // Summed: vector 500 + 900 over zstd -19 1000 + 1000; the second map is the worst, and there
  // zstd -3 is smaller than zstd -19.
  const std::vector<NamedComparison> maps = {{"small", Comparison(500, 1250, 1000)},
                                             {"large", Comparison(900, 900, 1000, 4)}};
  const TileBytesHeadline headline = HeadlineOf(maps);
  EXPECT_EQ(headline.summed.baseline, "zstd -19");
  EXPECT_DOUBLE_EQ(headline.summed.ratio, 1400.0 / 2000.0);
  EXPECT_EQ(headline.worst_map, "large");
  EXPECT_EQ(headline.worst.baseline, "zstd -3");
  EXPECT_DOUBLE_EQ(headline.worst.ratio, 1.0);

  TileBytesComparison total = maps[0].bytes;
  total += maps[1].bytes;
  EXPECT_EQ(total.grid.tiles, 5u);
  EXPECT_EQ(total.vector.tiles, 5u);
  EXPECT_EQ(total.grid.bytes.patch_cdr, 20000u);
  EXPECT_EQ(total.vector.payload, 1400u);
}

}  // namespace
}  // namespace fleetmap::bench
