#include "common/vector_map/chain_tracer.hpp"

#include <gtest/gtest.h>

#include "common/vector_map/skeleton.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

std::vector<PixelChain> Trace(const grid::OccupancyGrid& grid) {
  CellRaster raster(grid, CellRect{0, 0, grid.width(), grid.height()}, 6, {});
  const std::vector<int> skeleton = ThinToSkeleton(raster, std::sqrt(2.0));
  return TraceChains(raster, skeleton);
}

TEST(ChainTracerTest, CrossingWallsBecomeTwoChainsThroughTheJunction) {
  grid::OccupancyGrid grid(41, 41, 0.05, {}, grid::kFreeValue);
  testing::FillRect(grid, 5, 20, 35, 20, grid::kOccupiedValue);
  testing::FillRect(grid, 20, 5, 20, 35, grid::kOccupiedValue);
  const auto chains = Trace(grid);
  // Four arms meet at the centre: paired straight through, not four chains ending there.
  ASSERT_EQ(chains.size(), 2u);
  for (const PixelChain& chain : chains) {
    EXPECT_FALSE(chain.ring());
    EXPECT_GE(chain.pixels.size(), 25u);
  }
}

TEST(ChainTracerTest, TJunctionContinuesStraightAndLeavesOneStub) {
  grid::OccupancyGrid grid(41, 30, 0.05, {}, grid::kFreeValue);
  testing::FillRect(grid, 5, 20, 35, 20, grid::kOccupiedValue);  // the bar
  testing::FillRect(grid, 20, 5, 20, 19, grid::kOccupiedValue);  // the stem
  const auto chains = Trace(grid);
  ASSERT_EQ(chains.size(), 2u);
  // The longer chain is the bar, straight through the junction.
  const PixelChain& bar = chains[0].pixels.size() > chains[1].pixels.size() ? chains[0] : chains[1];
  EXPECT_GE(bar.pixels.size(), 27u);
}

TEST(ChainTracerTest, SquareRingIsOneRing) {
  grid::OccupancyGrid grid(30, 30, 0.05, {}, grid::kFreeValue);
  testing::FillRect(grid, 5, 5, 24, 5, grid::kOccupiedValue);
  testing::FillRect(grid, 5, 24, 24, 24, grid::kOccupiedValue);
  testing::FillRect(grid, 5, 5, 5, 24, grid::kOccupiedValue);
  testing::FillRect(grid, 24, 5, 24, 24, grid::kOccupiedValue);
  const auto chains = Trace(grid);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_TRUE(chains[0].ring());
}

}  // namespace
}  // namespace fleetmap::vector_map
