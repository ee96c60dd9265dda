#include "common/transport/internal/tile_region_filter.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fleetmap_msgs/msg/VectorTilePubSubTypes.h"

namespace fleetmap::transport {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// A VectorTile sample as the generated type support puts it on the wire.
SerializedPayload_t TileSample(const std::string& robot, int32_t x, int32_t y) {
  fleetmap_msgs::msg::dds_::VectorTile_ tile;
  tile.robot_id(robot);
  tile.tile_x(x);
  tile.tile_y(y);
  tile.geometry(std::vector<uint8_t>(10, 1));
  fleetmap_msgs::msg::dds_::VectorTile_PubSubType type;
  SerializedPayload_t payload(type.getSerializedSizeProvider(&tile)());
  EXPECT_TRUE(type.serialize(&tile, &payload));
  return payload;
}

TEST(ReadTileSampleKeyTest, ReadsRobotAndTileOfASerializedTileWhateverTheNameLength) {
  for (const std::string robot : {"a", "ab", "abc", "abcd", "robot_17"}) {
    const SerializedPayload_t payload = TileSample(robot, -3, 7);
    const std::optional<TileSampleKey> key = ReadTileSampleKey(payload);  // views into payload
    ASSERT_TRUE(key.has_value()) << robot;
    EXPECT_EQ(key->robot, robot);
    EXPECT_EQ(key->tile, (TileId{-3, 7})) << robot;
  }
}

TEST(ReadTileSampleKeyTest, RefusesAPayloadTooShortForTheTileKey) {
  SerializedPayload_t payload = TileSample("alpha", 1, 2);
  payload.length = 4 + 4 + 6 + 2 + 4;  // the string and tile_x, no tile_y
  EXPECT_EQ(ReadTileSampleKey(payload), std::nullopt);
  EXPECT_EQ(ReadTileSampleKey(SerializedPayload_t()), std::nullopt);
}

TEST(TileRegionSelectionTest, PassesItsOwnTilesAndTilesOnNoRegion) {
  TileRegionSelection selection;
  selection.own = TileBox{0, 0, 2, 5};
  selection.others = {TileBox{3, 0, 5, 5}};
  EXPECT_TRUE(selection.Passes(TileId{2, 5}));
  EXPECT_FALSE(selection.Passes(TileId{3, 0}));  // the other shard's
  EXPECT_TRUE(selection.Passes(TileId{9, 0}));   // on no region: reported
  // Not knowing the other shards, it cannot tell a tile on no region from theirs: it takes none.
  selection.others.clear();
  EXPECT_FALSE(selection.Passes(TileId{9, 0}));
}

TEST(TileRegionSelectionTest, ParametersRoundTripAndRefuseWhatTheyDoNotKnow) {
  TileRegionSelection selection;
  selection.own = TileBox{-4, -1, 2, 5};
  selection.others = {TileBox{3, -1, 5, 5}, TileBox{-9, -9, -5, -2}};
  StatusOr<TileRegionSelection> back =
      TileRegionSelection::FromParameters(selection.ToParameters());
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->own, selection.own);
  EXPECT_EQ(back->others, selection.others);

  EXPECT_FALSE(TileRegionSelection::FromParameters({"0", "1", "2"}).ok());
  EXPECT_FALSE(TileRegionSelection::FromParameters({"0", "1", "x", "3"}).ok());
  EXPECT_FALSE(TileRegionSelection::FromParameters({"0", "1", "2", "3", "box:1,2,3"}).ok());
  EXPECT_FALSE(TileRegionSelection::FromParameters({"0", "1", "2", "3", "robots:a"}).ok());
}

}  // namespace
}  // namespace fleetmap::transport
