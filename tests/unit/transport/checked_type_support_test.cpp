#include "common/transport/internal/checked_type_support.hpp"

#include <gtest/gtest.h>

#include "fleetmap_msgs/msg/RobotStatusPubSubTypes.h"
#include "fleetmap_msgs/msg/VectorTilePubSubTypes.h"

namespace fleetmap::transport {
namespace {

// Fast DDS computes a sample's key itself when the writer did not send its hash (Cyclone DDS
// does not): the generated code throws for a key string over 255 characters, on a thread where
// that aborts the process, and Fast DDS asserts on a sample left without an instance. The checked
// type support gives every such key one fixed, defined handle instead.
TEST(CheckedTypeSupportTest, AKeyThatCannotBeHashedGetsTheUnhashableHandle) {
  eprosima::fastdds::dds::TypeSupport type = VectorTileTypeSupport();
  fleetmap_msgs::msg::dds_::VectorTile_ tile;
  tile.robot_id(std::string(300, 'x'));
  eprosima::fastrtps::rtps::InstanceHandle_t tile_handle;
  bool hashed = false;
  EXPECT_NO_THROW(hashed = type->getKey(&tile, &tile_handle, false));
  EXPECT_TRUE(hashed);
  EXPECT_TRUE(tile_handle.isDefined());

  eprosima::fastdds::dds::TypeSupport status_type = RobotStatusTypeSupport();
  fleetmap_msgs::msg::dds_::RobotStatus_ status;
  status.robot_id(std::string(256, 'y'));
  eprosima::fastrtps::rtps::InstanceHandle_t status_handle;
  EXPECT_NO_THROW(hashed = status_type->getKey(&status, &status_handle, false));
  EXPECT_TRUE(hashed);
  EXPECT_EQ(status_handle, tile_handle);

  // An ordinary key never gets it.
  tile.robot_id("alpha");
  eprosima::fastrtps::rtps::InstanceHandle_t ordinary;
  ASSERT_TRUE(type->getKey(&tile, &ordinary, false));
  EXPECT_NE(ordinary, tile_handle);
}

TEST(CheckedTypeSupportTest, OrdinaryKeysHashAsTheGeneratedCodeDoes) {
  eprosima::fastdds::dds::TypeSupport type = VectorTileTypeSupport();
  fleetmap_msgs::msg::dds_::VectorTile_ tile;
  tile.robot_id("alpha");
  tile.tile_x(-3);
  tile.tile_y(7);
  eprosima::fastrtps::rtps::InstanceHandle_t checked;
  ASSERT_TRUE(type->getKey(&tile, &checked, false));
  fleetmap_msgs::msg::dds_::VectorTile_PubSubType generated;
  eprosima::fastrtps::rtps::InstanceHandle_t expected;
  ASSERT_TRUE(generated.getKey(&tile, &expected, false));
  EXPECT_EQ(checked, expected);
}

// A listener callback that throws is turned into a refusal: nothing escapes into Fast DDS.
TEST(CheckedTypeSupportTest, GuardListenerTurnsExceptionsIntoRefusals) {
  struct Sink : MalformedSink {
    std::string last;
    void OnMalformed(const Status& error) override { last = error.message(); }
  } sink;
  EXPECT_NO_THROW(GuardListener(&sink, "a test callback",
                                [] { throw std::length_error("basic_string::_M_create"); }));
  EXPECT_EQ(sink.refused(), 1u);
  EXPECT_NE(sink.last.find("a test callback failed: basic_string::_M_create"), std::string::npos);
  GuardListener(&sink, "a calm callback", [] {});
  EXPECT_EQ(sink.refused(), 1u);
}

}  // namespace
}  // namespace fleetmap::transport
