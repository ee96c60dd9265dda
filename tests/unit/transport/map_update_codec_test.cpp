#include "common/transport/map_update_codec.hpp"

#include <gtest/gtest.h>
#include <zstd.h>

#include <string>

namespace fleetmap::transport {
namespace {

MapUpdate Patch(int width, int height) {
  MapUpdate update;
  update.x = 2;
  update.y = 3;
  update.width = width;
  update.height = height;
  update.data.assign(static_cast<size_t>(width) * height, 0);
  for (size_t i = 0; i < update.data.size(); i += 7) update.data[i] = 100;
  update.data[1] = -1;
  update.frame_id = "alpha/map";
  return update;
}

::testing::AssertionResult RefusedSaying(const StatusOr<MapUpdate>& result,
                                         const std::string& text) {
  if (result.ok()) return ::testing::AssertionFailure() << "accepted";
  if (result.status().message().find(text) == std::string::npos) {
    return ::testing::AssertionFailure() << "refused with: " << result.status().message();
  }
  return ::testing::AssertionSuccess();
}

TEST(MapUpdateCodecTest, RoundTripsTheCellsAndTheRectangle) {
  const MapUpdate patch = Patch(40, 30);
  const auto compressed = CompressMapUpdate(patch, 3);
  ASSERT_TRUE(compressed.ok()) << compressed.status();
  EXPECT_EQ(compressed->compression, kZstdCompression);
  EXPECT_EQ(compressed->raw_size, 1200u);
  EXPECT_LT(compressed->data.size(), patch.data.size());
  const auto back = DecompressMapUpdate(*compressed, 1200);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->data, patch.data);
  EXPECT_EQ(back->x, 2);
  EXPECT_EQ(back->y, 3);
  EXPECT_EQ(back->width, 40);
  EXPECT_EQ(back->height, 30);
  EXPECT_EQ(back->frame_id, "alpha/map");
}

TEST(MapUpdateCodecTest, RefusesBadLevelsAndCountsWhenCompressing) {
  EXPECT_FALSE(CompressMapUpdate(Patch(4, 4), 0).ok());
  EXPECT_FALSE(CompressMapUpdate(Patch(4, 4), 23).ok());
  MapUpdate lying = Patch(4, 4);
  lying.data.pop_back();
  EXPECT_FALSE(CompressMapUpdate(lying, 3).ok());
}

TEST(MapUpdateCodecTest, RefusesALyingRawSizeBeforeAllocating) {
  auto compressed = CompressMapUpdate(Patch(40, 30), 3);
  ASSERT_TRUE(compressed.ok());
  CompressedMapUpdate lying = *compressed;
  lying.raw_size = 4'000'000'000u;
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(lying, 1 << 20), "raw_size 4000000000 is not"));
  // A rectangle (and raw_size) beyond what the receiver accepts.
  CompressedMapUpdate huge = *compressed;
  huge.width = 100000;
  huge.height = 10000;
  huge.raw_size = 1'000'000'000u;
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(huge, 1 << 20), "more than the 1048576 cells"));
}

TEST(MapUpdateCodecTest, RefusesAFrameThatDisagreesWithRawSize) {
  // A consistent header (raw_size = width x height) over a frame of another patch's cells.
  auto other = CompressMapUpdate(Patch(10, 10), 3);
  ASSERT_TRUE(other.ok());
  CompressedMapUpdate mixed = *other;
  mixed.width = 40;
  mixed.height = 30;
  mixed.raw_size = 1200;
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(mixed, 1200), "holds 100 bytes, not the 1200"));
}

TEST(MapUpdateCodecTest, RefusesCorruptAndForeignPayloads) {
  auto compressed = CompressMapUpdate(Patch(40, 30), 3);
  ASSERT_TRUE(compressed.ok());
  CompressedMapUpdate garbage = *compressed;
  garbage.data = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(garbage, 1200), "not a zstd frame"));

  CompressedMapUpdate truncated = *compressed;
  truncated.data.resize(truncated.data.size() / 2);
  EXPECT_FALSE(DecompressMapUpdate(truncated, 1200).ok());

  CompressedMapUpdate flipped = *compressed;
  flipped.data[flipped.data.size() - 3] ^= 0xff;
  flipped.data[flipped.data.size() / 2] ^= 0x55;
  EXPECT_FALSE(DecompressMapUpdate(flipped, 1200).ok());

  CompressedMapUpdate lz4 = *compressed;
  lz4.compression = 2;
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(lz4, 1200), "compression 2 is not zstd"));
}

TEST(MapUpdateCodecTest, RefusesAFrameWithoutItsContentSize) {
  // A streamed frame does not record its size: the receiver could not bound it up front.
  const MapUpdate patch = Patch(10, 10);
  ZSTD_CCtx* context = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(context, ZSTD_c_contentSizeFlag, 0);
  std::vector<uint8_t> frame(ZSTD_compressBound(patch.data.size()));
  const size_t size =
      ZSTD_compress2(context, frame.data(), frame.size(), patch.data.data(), patch.data.size());
  ZSTD_freeCCtx(context);
  ASSERT_FALSE(ZSTD_isError(size));
  frame.resize(size);
  CompressedMapUpdate update;
  update.width = 10;
  update.height = 10;
  update.raw_size = 100;
  update.data = frame;
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(update, 100), "does not record its content size"));
}

TEST(MapUpdateCodecTest, RefusesCellsOutsideTheOccupancyRange) {
  MapUpdate patch = Patch(4, 4);
  patch.data[5] = 101;
  auto compressed = CompressMapUpdate(patch, 3);
  ASSERT_TRUE(compressed.ok());
  EXPECT_TRUE(RefusedSaying(DecompressMapUpdate(*compressed, 16), "outside -1..100"));
}

}  // namespace
}  // namespace fleetmap::transport
