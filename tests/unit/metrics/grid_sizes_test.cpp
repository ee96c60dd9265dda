#include "common/metrics/grid_sizes.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fleetmap::metrics {
namespace {

TEST(GridSizesTest, CompressesAUniformGrid) {
  const grid::OccupancyGrid grid(200, 100, 0.05, {}, grid::kFreeValue);
  const GridSizes sizes = *MeasureGridSizes(grid);
  EXPECT_EQ(sizes.cells.raw, 20000u);
  EXPECT_GT(sizes.cells.gzip, 18u);  // gzip header and trailer alone are 18 bytes
  EXPECT_LT(sizes.cells.gzip, 200u);
  EXPECT_LT(sizes.cells.zstd, 100u);
  EXPECT_GT(sizes.png, 0u);
  EXPECT_LT(sizes.png, 1000u);
}

TEST(GridSizesTest, MeasuresAnyBuffer) {
  const std::vector<uint8_t> empty;
  const CompressedSizes none = *MeasureBytes(empty);
  EXPECT_EQ(none.raw, 0u);
  EXPECT_GT(none.gzip, 0u);
  std::vector<uint8_t> noise(4096);
  uint32_t state = 12345;
  for (auto& b : noise) b = static_cast<uint8_t>((state = state * 1664525u + 1013904223u) >> 24);
  const CompressedSizes sizes = *MeasureBytes(noise);
  EXPECT_EQ(sizes.raw, 4096u);
  EXPECT_GT(sizes.zstd, 4000u);  // random bytes do not compress
}

TEST(GridSizesTest, EmptyGridHasNoPng) {
  const GridSizes sizes = *MeasureGridSizes(grid::OccupancyGrid());
  EXPECT_EQ(sizes.cells.raw, 0u);
  EXPECT_EQ(sizes.png, 0u);
}

}  // namespace
}  // namespace fleetmap::metrics
