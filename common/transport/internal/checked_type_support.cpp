#include "common/transport/internal/checked_type_support.hpp"

#include "common/transport/internal/idl_shapes.hpp"
#include "fleetmap_msgs/msg/CompressedGridUpdatePubSubTypes.h"
#include "fleetmap_msgs/msg/EntityPubSubTypes.h"
#include "fleetmap_msgs/msg/FleetServerPubSubTypes.h"
#include "fleetmap_msgs/msg/ObjectModelPubSubTypes.h"
#include "fleetmap_msgs/msg/ObjectTemplatePubSubTypes.h"
#include "fleetmap_msgs/msg/RobotAdmissionPubSubTypes.h"
#include "fleetmap_msgs/msg/RobotFramePubSubTypes.h"
#include "fleetmap_msgs/msg/RobotStatusPubSubTypes.h"
#include "fleetmap_msgs/msg/RouteGraphPubSubTypes.h"
#include "fleetmap_msgs/msg/SubmapPubSubTypes.h"
#include "fleetmap_msgs/msg/VectorTilePubSubTypes.h"
#include "map_msgs/msg/OccupancyGridUpdatePubSubTypes.h"
#include "nav_msgs/msg/OccupancyGridPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace fleetmap::transport {
namespace {

thread_local MalformedSink* current_sink = nullptr;

}  // namespace

ScopedMalformedSink::ScopedMalformedSink(MalformedSink* sink) : previous_(current_sink) {
  current_sink = sink;
}

ScopedMalformedSink::~ScopedMalformedSink() { current_sink = previous_; }

MalformedSink* ScopedMalformedSink::Current() { return current_sink; }

eprosima::fastdds::dds::TypeSupport RobotStatusTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::RobotStatus_PubSubType>(RobotStatusShape()));
}

eprosima::fastdds::dds::TypeSupport OccupancyGridTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<nav_msgs::msg::dds_::OccupancyGrid_PubSubType>(OccupancyGridShape()));
}

eprosima::fastdds::dds::TypeSupport OccupancyGridUpdateTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<map_msgs::msg::dds_::OccupancyGridUpdate_PubSubType>(
          OccupancyGridUpdateShape()));
}

eprosima::fastdds::dds::TypeSupport CompressedGridUpdateTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::CompressedGridUpdate_PubSubType>(
          CompressedGridUpdateShape()));
}

eprosima::fastdds::dds::TypeSupport VectorTileTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::VectorTile_PubSubType>(VectorTileShape()));
}

eprosima::fastdds::dds::TypeSupport EntityTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::Entity_PubSubType>(EntityShape()));
}

eprosima::fastdds::dds::TypeSupport SubmapTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::Submap_PubSubType>(SubmapShape()));
}

eprosima::fastdds::dds::TypeSupport ObjectTemplateTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::ObjectTemplate_PubSubType>(
          ObjectTemplateShape()));
}

eprosima::fastdds::dds::TypeSupport ObjectModelTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::ObjectModel_PubSubType>(ObjectModelShape()));
}

eprosima::fastdds::dds::TypeSupport RobotFrameTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::RobotFrame_PubSubType>(RobotFrameShape()));
}

eprosima::fastdds::dds::TypeSupport RobotAdmissionTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::RobotAdmission_PubSubType>(
          RobotAdmissionShape()));
}

eprosima::fastdds::dds::TypeSupport FleetServerTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::FleetServer_PubSubType>(FleetServerShape()));
}

eprosima::fastdds::dds::TypeSupport RouteGraphTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<fleetmap_msgs::msg::dds_::RouteGraph_PubSubType>(RouteGraphShape()));
}

eprosima::fastdds::dds::TypeSupport TfMessageTypeSupport() {
  return eprosima::fastdds::dds::TypeSupport(
      new CheckedPubSubType<tf2_msgs::msg::dds_::TFMessage_PubSubType>(TfMessageShape()));
}

}  // namespace fleetmap::transport
