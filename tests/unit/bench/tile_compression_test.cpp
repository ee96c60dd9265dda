#include "bench/bytes/tile_compression.hpp"

#include <gtest/gtest.h>
#include <lz4.h>
#include <zstd.h>

#include <cstdint>
#include <vector>

namespace fleetmap::bench {
namespace {

// A tile-like buffer: unknown, then a free room crossed by a wall, as int8 cells.
std::vector<uint8_t> TileCells() {
  std::vector<uint8_t> cells(200 * 200, static_cast<uint8_t>(-1));
  for (int y = 40; y < 160; ++y) {
    for (int x = 30; x < 170; ++x) cells[y * 200 + x] = (x == 100 || y == 40) ? 100 : 0;
  }
  return cells;
}

TEST(TileCompressionTest, ZstdOutputDecompressesToTheInput) {
  const std::vector<uint8_t> cells = TileCells();
  for (const int level : {3, 19}) {
    const StatusOr<std::vector<uint8_t>> compressed = CompressZstd(cells, level);
    ASSERT_TRUE(compressed.ok()) << compressed.status();
    EXPECT_LT(compressed->size(), cells.size() / 10) << "level " << level;
    // The frame says its content size, as a receiver needs it.
    EXPECT_EQ(ZSTD_getFrameContentSize(compressed->data(), compressed->size()), cells.size());
    std::vector<uint8_t> back(cells.size());
    const size_t size =
        ZSTD_decompress(back.data(), back.size(), compressed->data(), compressed->size());
    ASSERT_FALSE(ZSTD_isError(size)) << ZSTD_getErrorName(size);
    EXPECT_EQ(back, cells) << "level " << level;
  }
}

TEST(TileCompressionTest, HigherZstdLevelIsNoLarger) {
  const std::vector<uint8_t> cells = TileCells();
  EXPECT_LE(CompressZstd(cells, 19)->size(), CompressZstd(cells, 3)->size());
}

TEST(TileCompressionTest, RefusesAZstdLevelOutOfRange) {
  const std::vector<uint8_t> cells = TileCells();
  EXPECT_FALSE(CompressZstd(cells, 0).ok());
  EXPECT_FALSE(CompressZstd(cells, ZSTD_maxCLevel() + 1).ok());
}

TEST(TileCompressionTest, Lz4BlockDecompressesToTheInputOfKnownSize) {
  const std::vector<uint8_t> cells = TileCells();
  const StatusOr<std::vector<uint8_t>> compressed = CompressLz4(cells);
  ASSERT_TRUE(compressed.ok()) << compressed.status();
  EXPECT_LT(compressed->size(), cells.size() / 10);
  std::vector<uint8_t> back(cells.size());
  const int size = LZ4_decompress_safe(
      reinterpret_cast<const char*>(compressed->data()), reinterpret_cast<char*>(back.data()),
      static_cast<int>(compressed->size()), static_cast<int>(back.size()));
  ASSERT_EQ(size, static_cast<int>(cells.size()));
  EXPECT_EQ(back, cells);
}

}  // namespace
}  // namespace fleetmap::bench
