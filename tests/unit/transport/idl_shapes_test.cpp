#include "common/transport/internal/idl_shapes.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <gtest/gtest.h>

#include <string>

#include "fleetmap_msgs/msg/CompressedGridUpdate.h"
#include "fleetmap_msgs/msg/Entity.h"
#include "fleetmap_msgs/msg/ObjectModel.h"
#include "fleetmap_msgs/msg/ObjectTemplate.h"
#include "fleetmap_msgs/msg/RobotFrame.h"
#include "fleetmap_msgs/msg/RobotStatus.h"
#include "fleetmap_msgs/msg/RouteGraph.h"
#include "fleetmap_msgs/msg/Submap.h"
#include "fleetmap_msgs/msg/VectorMap.h"
#include "map_msgs/msg/OccupancyGridUpdate.h"
#include "nav_msgs/msg/OccupancyGrid.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace fleetmap::transport {
namespace {

// Serializes a sample as Fast DDS would (encapsulation + CDR, either endianness).
template <typename T>
std::string Serialize(const T& sample, eprosima::fastcdr::Cdr::Endianness endianness) {
  std::string bytes(T::getCdrSerializedSize(sample) + 4, '\0');
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, endianness, eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  sample.serialize(cdr);
  bytes.resize(cdr.getSerializedDataLength());
  return bytes;
}

// The shape must walk exactly the bytes fastcdr wrote, and refuse every shorter prefix.
template <typename T>
void ExpectShapeMatches(const T& sample, const CdrShape& shape) {
  for (const auto endianness :
       {eprosima::fastcdr::Cdr::BIG_ENDIANNESS, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS}) {
    const std::string bytes = Serialize(sample, endianness);
    const std::span<const uint8_t> payload(reinterpret_cast<const uint8_t*>(bytes.data()),
                                           bytes.size());
    size_t consumed = 0;
    const Status checked = CheckCdr(payload, shape, &consumed);
    ASSERT_TRUE(checked.ok()) << checked;
    EXPECT_EQ(consumed + 4, bytes.size());
    for (size_t length = 0; length < bytes.size(); ++length) {
      EXPECT_FALSE(CheckCdr(payload.first(length), shape).ok()) << "prefix " << length;
    }
  }
}

TEST(IdlShapesTest, OccupancyGridShapeMatchesGeneratedCode) {
  nav_msgs::msg::dds_::OccupancyGrid_ grid;
  grid.header().frame_id("alpha/map");
  grid.info().width(3);
  grid.info().height(2);
  grid.data({0, 100, -1, 0, 0, 100});
  ExpectShapeMatches(grid, OccupancyGridShape());
}

TEST(IdlShapesTest, RobotStatusShapeMatchesGeneratedCode) {
  fleetmap_msgs::msg::dds_::RobotStatus_ status;
  status.robot_id("r");  // an odd length, so the padding after strings is exercised
  status.map_topic("rt/r/map");
  status.bytes_published(12345);
  status.baseline_zstd3_bytes(678);
  status.baseline_patches_pending(3);
  ExpectShapeMatches(status, RobotStatusShape());
}

TEST(IdlShapesTest, GridUpdateShapesMatchGeneratedCode) {
  map_msgs::msg::dds_::OccupancyGridUpdate_ update;
  update.header().frame_id("a/map");
  update.x(4);
  update.width(3);
  update.height(1);
  update.data({0, 100, -1});
  ExpectShapeMatches(update, OccupancyGridUpdateShape());
  fleetmap_msgs::msg::dds_::CompressedGridUpdate_ compressed;
  compressed.header().frame_id("a/map");
  compressed.width(3);
  compressed.height(1);
  compressed.compression(1);  // a uint8 before a uint32: the padding is exercised
  compressed.raw_size(3);
  compressed.data({40, 181, 47});
  ExpectShapeMatches(compressed, CompressedGridUpdateShape());
}

TEST(IdlShapesTest, VectorMapShapeMatchesGeneratedCode) {
  fleetmap_msgs::msg::dds_::VectorTile_ tile;
  tile.robot_id("ab");  // an odd length, so the padding before the float64 quantum is exercised
  tile.geometry({1, 2, 3});
  fleetmap_msgs::msg::dds_::VectorMap_ map;
  map.format("fleetmap-vmap/5");
  map.frame_id("fleet");
  map.tiles({tile, tile});
  ExpectShapeMatches(tile, VectorTileShape());
  ExpectShapeMatches(map, VectorMapShape());
  // An empty geometry and robot id, as in a .vmap file.
  fleetmap_msgs::msg::dds_::VectorTile_ empty;
  ExpectShapeMatches(empty, VectorTileShape());
}

TEST(IdlShapesTest, VmapFormatShapeIsTheFirstFieldOfAVectorMap) {
  fleetmap_msgs::msg::dds_::VectorMap_ map;
  map.format("fleetmap-vmap/5");
  map.frame_id("fleet");
  const std::string bytes = Serialize(map, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS);
  const std::span<const uint8_t> payload(reinterpret_cast<const uint8_t*>(bytes.data()),
                                         bytes.size());
  size_t consumed = 0;
  ASSERT_TRUE(CheckCdr(payload, VmapFormatShape(), &consumed).ok());
  EXPECT_EQ(consumed, 4 + map.format().size() + 1);  // the length, the characters, the NUL
}

TEST(CdrShapeTest, RefusesAHugeSequenceLengthWithoutAllocating) {
  nav_msgs::msg::dds_::OccupancyGrid_ grid;
  grid.data({1, 2, 3});
  std::string bytes = Serialize(grid, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS);
  // The data length is the last uint32 before the 3 data bytes.
  const size_t length_at = bytes.size() - 3 - 4;
  bytes[length_at + 3] = '\x7f';  // 0x7f000003 elements
  const std::span<const uint8_t> payload(reinterpret_cast<const uint8_t*>(bytes.data()),
                                         bytes.size());
  const Status checked = CheckCdr(payload, OccupancyGridShape());
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.message().find("data claims"), std::string::npos) << checked;
}

TEST(IdlShapesTest, EntityShapeMatchesGeneratedCode) {
  fleetmap_msgs::msg::dds_::Entity_ entity;
  entity.robot_id("r");
  entity.entity_id("door_1");
  entity.frame_id("map");
  entity.entity_class(3);
  entity.x({1.0, 2.0, 3.0});
  entity.y({0.5, 0.5, 0.5});
  entity.track_stamps({0.0, 0.5, 1.0});
  entity.track_headings({0.0, 0.0, 0.1});
  entity.dominant_side(-1);
  entity.entered_view(true);
  ExpectShapeMatches(entity, EntityShape());
}

TEST(IdlShapesTest, SubmapShapeMatchesGeneratedCode) {
  fleetmap_msgs::msg::dds_::Submap_ submap;
  submap.submap_id(7);
  submap.frame_id("fleet");
  submap.kind(2);
  submap.source_robot("abc");
  submap.source_entity("d");
  submap.width(3);
  submap.height(1);
  submap.data({0, -1, 0});
  submap.edge_to({1});
  submap.edge_x({1.5});
  submap.edge_y({-2.0});
  submap.edge_theta({0.25});
  submap.edge_entity({"alpha/door_1"});
  ExpectShapeMatches(submap, SubmapShape());
}

TEST(IdlShapesTest, RouteGraphShapeMatchesGeneratedCode) {
  fleetmap_msgs::msg::dds_::RouteGraph_ graph;
  graph.graph_id("fleet");
  graph.revision(3);
  graph.frame("map");
  graph.robot_radius(0.3);
  graph.clearance_margin(0.05);
  graph.node_id({1, 2});
  graph.node_x({0.5, 1.5});
  graph.node_y({-1.0, 2.0});
  graph.node_kind({0, 4});
  graph.node_clearance({0.4F, 0.5F});
  graph.edge_id({3});
  graph.edge_reverse_id({4});
  graph.edge_start({1});
  graph.edge_end({2});
  graph.edge_length({3.2F});
  graph.edge_clearance({0.35F});
  graph.node_flags({0, 1});
  graph.edge_flags({3});
  graph.edge_object({9});
  graph.note("two parts");
  ExpectShapeMatches(graph, RouteGraphShape());
}

TEST(IdlShapesTest, ObjectShapesMatchGeneratedCode) {
  fleetmap_msgs::msg::dds_::ObjectTemplate_ object_template;
  object_template.template_id(2);
  object_template.width(3);
  object_template.height(1);
  object_template.data({0, 50, 100});
  ExpectShapeMatches(object_template, ObjectTemplateShape());
  fleetmap_msgs::msg::dds_::ObjectModel_ object;
  object.object_id(4);
  object.width(1);
  object.height(1);
  object.data({100});
  object.sighting_session({0, 3});
  object.sighting_x({1.0, 2.0});
  object.sighting_y({1.0, 2.0});
  object.sighting_theta({0.0, 1.5});
  ExpectShapeMatches(object, ObjectModelShape());
}

TEST(IdlShapesTest, RobotFrameAndTfShapesMatchGeneratedCode) {
  fleetmap_msgs::msg::dds_::RobotFrame_ frame;
  frame.robot_id("beta");
  frame.state(2);
  frame.fleet_from_map().x(3.5);
  frame.confidence(0.9);
  frame.placements(2);
  frame.placed_against("fleet");
  ExpectShapeMatches(frame, RobotFrameShape());
  tf2_msgs::msg::dds_::TFMessage_ tf;
  for (const char* child : {"alpha/map", "beta/map"}) {
    geometry_msgs::msg::dds_::TransformStamped_ transform;
    transform.header().frame_id("fleet");
    transform.child_frame_id(child);
    transform.transform().rotation().w(1.0);
    tf.transforms().push_back(transform);
  }
  ExpectShapeMatches(tf, TfMessageShape());
}

}  // namespace
}  // namespace fleetmap::transport
