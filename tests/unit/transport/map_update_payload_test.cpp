#include "common/transport/map_update_payload.hpp"

#include <gtest/gtest.h>

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/idl_shapes.hpp"

namespace fleetmap::transport {
namespace {

// A 3 x 2 patch at (7, 11) with every cell state, as a SLAM node sends after a scan.
MapUpdate SmallPatch() {
  MapUpdate update;
  update.x = 7;
  update.y = 11;
  update.width = 3;
  update.height = 2;
  update.data = {100, 0, -1, 0, 0, 100};
  update.stamp = Timestamp(std::chrono::seconds(1700000000));
  return update;
}

TEST(MapUpdatePayloadTest, SizeIsTheCdrLayoutOfTheMessage) {
  // Encapsulation 4; stamp sec + nanosec 8; frame_id length 4 + "map\0" 4; x, y, width, height
  // 16; data length 4; then one byte per cell, no padding after the last.
  constexpr size_t kHeaderBytes = 4 + 8 + 4 + 4 + 16 + 4;
  const MapUpdate patch = SmallPatch();
  EXPECT_EQ(EncodeMapUpdatePayload(patch, "map").size(), kHeaderBytes + 6);
  // An empty frame id ("\0") is padded to the same 4 bytes; a longer one to the next multiple.
  EXPECT_EQ(EncodeMapUpdatePayload(patch, "").size(), kHeaderBytes + 6);
  EXPECT_EQ(EncodeMapUpdatePayload(patch, "robot0/map").size(), kHeaderBytes + 8 + 6);

  MapUpdate tile = patch;
  tile.width = 200;
  tile.height = 200;
  tile.data.assign(200 * 200, -1);
  EXPECT_EQ(EncodeMapUpdatePayload(tile, "map").size(), kHeaderBytes + 40000);
}

TEST(MapUpdatePayloadTest, DecodesAsTheSampleARosPeerReads) {
  const MapUpdate patch = SmallPatch();
  const std::string bytes = EncodeMapUpdatePayload(patch, "map");
  map_msgs::msg::dds_::OccupancyGridUpdate_ sample;
  ASSERT_TRUE(
      DeserializeCdr(bytes, OccupancyGridUpdateShape(), "not an OccupancyGridUpdate", &sample)
          .ok());
  EXPECT_EQ(sample.header().frame_id(), "map");
  const StatusOr<MapUpdate> back = FromIdl(sample);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->x, 7);
  EXPECT_EQ(back->y, 11);
  EXPECT_EQ(back->width, 3);
  EXPECT_EQ(back->height, 2);
  EXPECT_EQ(back->data, patch.data);
  EXPECT_EQ(back->stamp, patch.stamp);
}

}  // namespace
}  // namespace fleetmap::transport
