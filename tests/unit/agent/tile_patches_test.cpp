#include "robot_agent/tile_patches.hpp"

#include <gtest/gtest.h>

namespace fleetmap::agent {
namespace {

const Transform2 kIdentity = Pose2{}.ToTransform();

// 10 m tiles at 1 m cells: a 25 x 12 grid at the fleet origin spans tiles x 0..2, y 0..1.
grid::OccupancyGrid Grid() {
  return grid::OccupancyGrid(25, 12, 1.0, Pose2{}, grid::kUnknownValue);
}

TEST(TilePatchesTest, ChangedTilesAreThoseWhoseCellsDiffer) {
  const grid::OccupancyGrid before = Grid();
  grid::OccupancyGrid after = before;
  after.at(13, 4) = grid::kOccupiedValue;  // tile (1, 0)
  after.at(24, 11) = grid::kFreeValue;     // tile (2, 1)
  const auto changed = ChangedTiles(before, after, kIdentity, 10.0);
  ASSERT_TRUE(changed.ok()) << changed.status();
  ASSERT_EQ(changed->size(), 2u);
  EXPECT_EQ((*changed)[0].tile, (TileId{1, 0}));
  EXPECT_EQ((*changed)[0].rect, (grid::CellRect{10, 0, 10, 10}));
  EXPECT_EQ((*changed)[1].tile, (TileId{2, 1}));
  EXPECT_EQ((*changed)[1].rect, (grid::CellRect{20, 10, 5, 2}));
  const auto none = ChangedTiles(after, after, kIdentity, 10.0);
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

TEST(TilePatchesTest, KnownTilesSkipAllUnknownTiles) {
  grid::OccupancyGrid map = Grid();
  map.at(3, 3) = grid::kFreeValue;
  const auto known = KnownTiles(map, kIdentity, 10.0);
  ASSERT_TRUE(known.ok());
  ASSERT_EQ(known->size(), 1u);
  EXPECT_EQ((*known)[0].tile, (TileId{0, 0}));
}

TEST(TilePatchesTest, APatchCarriesTheRectangleRowMajor) {
  grid::OccupancyGrid map = Grid();
  map.at(21, 10) = grid::kOccupiedValue;
  map.at(20, 11) = grid::kFreeValue;
  const transport::MapUpdate patch = PatchOf(map, grid::CellRect{20, 10, 5, 2});
  EXPECT_EQ(patch.x, 20);
  EXPECT_EQ(patch.y, 10);
  EXPECT_EQ(patch.width, 5);
  EXPECT_EQ(patch.height, 2);
  ASSERT_EQ(patch.data.size(), 10u);
  EXPECT_EQ(patch.data[1], grid::kOccupiedValue);
  EXPECT_EQ(patch.data[5], grid::kFreeValue);
  grid::OccupancyGrid copy = Grid();
  ASSERT_TRUE(transport::ApplyMapUpdate(patch, &copy).ok());
  EXPECT_EQ(copy.at(21, 10), grid::kOccupiedValue);
}

TEST(TilePatchesTest, GeometryIsSizeResolutionAndOrigin) {
  EXPECT_TRUE(SameGeometry(Grid(), Grid()));
  EXPECT_FALSE(SameGeometry(Grid(), grid::OccupancyGrid(25, 13, 1.0, Pose2{}, 0)));
  EXPECT_FALSE(SameGeometry(Grid(), grid::OccupancyGrid(25, 12, 0.5, Pose2{}, 0)));
  EXPECT_FALSE(SameGeometry(Grid(), grid::OccupancyGrid(25, 12, 1.0, Pose2{1.0, 0.0, 0.0}, 0)));
}

}  // namespace
}  // namespace fleetmap::agent
