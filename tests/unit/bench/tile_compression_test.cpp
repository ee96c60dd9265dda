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

// Buffers that share one block of 4 KB of noise (which no buffer compresses alone) and differ
// in a few bytes: what a dictionary is for.
std::vector<std::vector<uint8_t>> SharedBlockSamples(int count, uint32_t seed) {
  std::vector<uint8_t> block(4096);
  uint32_t state = 12345;
  for (uint8_t& byte : block) {
    state = state * 1664525u + 1013904223u;
    byte = static_cast<uint8_t>(state >> 24);
  }
  std::vector<std::vector<uint8_t>> samples;
  for (int i = 0; i < count; ++i) {
    std::vector<uint8_t> sample = block;
    sample[static_cast<size_t>((seed + 97u * static_cast<uint32_t>(i)) % block.size())] ^= 0x5a;
    samples.push_back(std::move(sample));
  }
  return samples;
}

TEST(ZstdDictionaryTest, ADictionaryOfWhatTilesShareMakesThemSmallerAndRoundTrips) {
  const StatusOr<ZstdDictionary> dictionary = ZstdDictionary::Train(SharedBlockSamples(64, 1));
  ASSERT_TRUE(dictionary.ok()) << dictionary.status();
  EXPECT_GT(dictionary->size(), 0u);
  EXPECT_LE(dictionary->size(), ZstdDictionary::kDefaultCapacity);
  // A tile it was not trained on, with the same shared block.
  const std::vector<uint8_t> tile = SharedBlockSamples(1, 7).front();
  const StatusOr<std::vector<uint8_t>> with = dictionary->Compress(tile, 19);
  ASSERT_TRUE(with.ok()) << with.status();
  const StatusOr<std::vector<uint8_t>> alone = CompressZstd(tile, 19);
  ASSERT_TRUE(alone.ok()) << alone.status();
  EXPECT_LT(with->size() * 10, alone->size());  // the block is in the dictionary
  // The frame still says its content size, and decodes to the tile with the dictionary.
  EXPECT_EQ(ZSTD_getFrameContentSize(with->data(), with->size()), tile.size());
  const StatusOr<std::vector<uint8_t>> back = dictionary->Decompress(*with);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(*back, tile);
}

TEST(ZstdDictionaryTest, TooFewSamplesOrABadLevelAreRefusedByName) {
  const StatusOr<ZstdDictionary> few = ZstdDictionary::Train(SharedBlockSamples(3, 1));
  ASSERT_FALSE(few.ok());
  EXPECT_NE(few.status().message().find("at least 8 samples"), std::string::npos) << few.status();
  const StatusOr<ZstdDictionary> dictionary = ZstdDictionary::Train(SharedBlockSamples(64, 1));
  ASSERT_TRUE(dictionary.ok()) << dictionary.status();
  EXPECT_FALSE(dictionary->Compress(TileCells(), 0).ok());
  EXPECT_FALSE(dictionary->Decompress(std::vector<uint8_t>{1, 2, 3}).ok());
}

}  // namespace
}  // namespace fleetmap::bench
