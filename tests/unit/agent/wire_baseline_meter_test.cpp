#include "robot_agent/wire_baseline_meter.hpp"

#include <gtest/gtest.h>

#include "common/transport/map_update_codec.hpp"
#include "common/transport/wire_sizes.hpp"
#include "robot_agent/tile_patches.hpp"

namespace fleetmap::agent {
namespace {

// 10 m tiles at 0.5 m cells: a 40 x 30 grid at the fleet origin spans 2 x 2 tiles (20 x 20 cells).
grid::OccupancyGrid Grid() {
  return grid::OccupancyGrid(40, 30, 0.5, Pose2{}, grid::kUnknownValue);
}

TEST(WireBaselineMeterTest, CountsWholeGridsAndThePatchesOfChangedTilesOnly) {
  auto meter = WireBaselineMeter::Create(RobotId{"alpha"}, Pose2{}, 10.0);
  ASSERT_TRUE(meter.ok()) << meter.status();
  grid::OccupancyGrid map = Grid();
  for (int x = 0; x < 15; ++x) map.at(x, 3) = grid::kFreeValue;  // tile (0, 0) only
  ASSERT_TRUE((*meter)->Account(map).ok());
  ASSERT_TRUE((*meter)->Account(map).ok());  // no change: no wire sends anything
  map.at(25, 25) = grid::kOccupiedValue;     // tile (1, 1)
  ASSERT_TRUE((*meter)->Account(map).ok());
  (*meter)->Hurry();
  ASSERT_TRUE((*meter)->WaitUntilDone(std::chrono::milliseconds(30000)));

  const WireBaselines totals = (*meter)->totals();
  EXPECT_EQ(totals.events, 2u);
  EXPECT_EQ(totals.patches_pending, 0u);
  // Every figure is the size of the sample the real type support writes.
  transport::MapMessage whole;
  whole.grid = map;
  whole.frame_id = "alpha/map";
  EXPECT_EQ(totals.grid_bytes, 2 * transport::OccupancyGridPayloadBytes(whole));
  // The first grid as the patch of its one known tile, then the one changed tile.
  transport::MapUpdate first = PatchOf(map, grid::CellRect{0, 0, 20, 20});
  first.frame_id = "alpha/map";
  transport::MapUpdate second = PatchOf(map, grid::CellRect{20, 20, 20, 10});
  second.frame_id = "alpha/map";
  EXPECT_EQ(totals.patch_bytes,
            transport::MapUpdatePayloadBytes(first) + transport::MapUpdatePayloadBytes(second));
  const auto zstd3 = [](const transport::MapUpdate& patch) {
    return transport::CompressedMapUpdatePayloadBytes(*transport::CompressMapUpdate(patch, 3));
  };
  EXPECT_EQ(totals.zstd3_bytes, zstd3(first) + zstd3(second));
  EXPECT_LT(totals.zstd19_bytes, totals.patch_bytes);
  EXPECT_LT(totals.lz4_bytes, totals.patch_bytes);
  EXPECT_GT(totals.lz4_bytes, 0u);
}

TEST(WireBaselineMeterTest, AGridOfAnotherGeometryCountsAsNew) {
  auto meter = WireBaselineMeter::Create(RobotId{"alpha"}, Pose2{}, 10.0);
  ASSERT_TRUE(meter.ok());
  grid::OccupancyGrid map = Grid();
  map.at(1, 1) = grid::kFreeValue;
  ASSERT_TRUE((*meter)->Account(map).ok());
  grid::OccupancyGrid grown(60, 30, 0.5, Pose2{}, grid::kUnknownValue);
  grown.at(1, 1) = grid::kFreeValue;
  grown.at(45, 1) = grid::kFreeValue;  // tile (2, 0)
  ASSERT_TRUE((*meter)->Account(grown).ok());
  (*meter)->Hurry();
  ASSERT_TRUE((*meter)->WaitUntilDone(std::chrono::milliseconds(30000)));
  // Both known tiles of the grown grid are sent again: nothing of the old geometry carries over.
  transport::MapUpdate a = PatchOf(map, grid::CellRect{0, 0, 20, 20});
  transport::MapUpdate b = PatchOf(grown, grid::CellRect{0, 0, 20, 20});
  transport::MapUpdate c = PatchOf(grown, grid::CellRect{40, 0, 20, 20});
  for (auto* patch : {&a, &b, &c}) patch->frame_id = "alpha/map";
  EXPECT_EQ((*meter)->totals().patch_bytes, transport::MapUpdatePayloadBytes(a) +
                                                transport::MapUpdatePayloadBytes(b) +
                                                transport::MapUpdatePayloadBytes(c));
}

}  // namespace
}  // namespace fleetmap::agent
