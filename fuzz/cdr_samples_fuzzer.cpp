// Fuzz target: an incoming DDS sample of every topic type fleetmap reads, as the type support a
// reader registers receives it (checked_type_support.hpp): the CDR shape check, fastcdr's decode,
// the key hash, then the conversion the reader applies (FromIdl, and for the compressed patch wire
// the decompression). The first byte picks the type; the rest is the serialized payload.
//
// Besides crashes, one property: a sample the shape check let through re-serializes to bytes the
// same shape accepts, so the shapes (idl_shapes.cpp) and fastcdr agree on what they read.

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "common/core/check.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/idl_shapes.hpp"
#include "common/transport/internal/state_conversions.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/map_update_codec.hpp"
#include "fleetmap_msgs/msg/CompressedGridUpdatePubSubTypes.h"
#include "fleetmap_msgs/msg/EntityPubSubTypes.h"
#include "fleetmap_msgs/msg/ObjectModelPubSubTypes.h"
#include "fleetmap_msgs/msg/ObjectTemplatePubSubTypes.h"
#include "fleetmap_msgs/msg/RobotFramePubSubTypes.h"
#include "fleetmap_msgs/msg/RobotStatusPubSubTypes.h"
#include "fleetmap_msgs/msg/RouteGraphPubSubTypes.h"
#include "fleetmap_msgs/msg/SubmapPubSubTypes.h"
#include "fleetmap_msgs/msg/VectorTilePubSubTypes.h"
#include "map_msgs/msg/OccupancyGridUpdatePubSubTypes.h"
#include "nav_msgs/msg/OccupancyGridPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace {

using namespace fleetmap;
using namespace fleetmap::transport;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// Receives `bytes` as a sample of `PubSubType` and, when the type support takes it, hands it to
// `convert`.
template <typename PubSubType, typename Convert>
void Receive(const CdrShape& shape, std::span<const uint8_t> bytes, Convert convert) {
  CheckedPubSubType<PubSubType> type(shape);
  SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  if (!bytes.empty()) std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<uint32_t>(bytes.size());
  typename PubSubType::type sample;
  if (!type.deserialize(&payload, &sample)) return;
  eprosima::fastrtps::rtps::InstanceHandle_t handle;
  type.getKey(&sample, &handle, false);
  convert(sample);

  SerializedPayload_t again(type.getSerializedSizeProvider(&sample)());
  FLEETMAP_CHECK(type.serialize(&sample, &again), "an accepted sample does not serialize");
  const Status checked = CheckCdr(std::span<const uint8_t>(again.data, again.length), shape);
  FLEETMAP_CHECK(checked.ok(), checked.message());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::span<const uint8_t> bytes(data + 1, size - 1);
  switch (data[0] % 12) {
    case 0:
      Receive<fleetmap_msgs::msg::dds_::VectorTile_PubSubType>(
          VectorTileShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 1:
      Receive<fleetmap_msgs::msg::dds_::RobotStatus_PubSubType>(
          RobotStatusShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 2:
      Receive<nav_msgs::msg::dds_::OccupancyGrid_PubSubType>(
          OccupancyGridShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 3:
      Receive<map_msgs::msg::dds_::OccupancyGridUpdate_PubSubType>(
          OccupancyGridUpdateShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 4:
      Receive<fleetmap_msgs::msg::dds_::CompressedGridUpdate_PubSubType>(
          CompressedGridUpdateShape(), bytes, [](const auto& sample) {
            const StatusOr<CompressedMapUpdate> update = FromIdl(sample);
            if (update.ok()) (void)DecompressMapUpdate(*update, size_t{1} << 20);
          });
      break;
    case 5:
      Receive<fleetmap_msgs::msg::dds_::Entity_PubSubType>(
          EntityShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 6:
      Receive<fleetmap_msgs::msg::dds_::Submap_PubSubType>(
          SubmapShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 7:
      Receive<fleetmap_msgs::msg::dds_::ObjectTemplate_PubSubType>(
          ObjectTemplateShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 8:
      Receive<fleetmap_msgs::msg::dds_::ObjectModel_PubSubType>(
          ObjectModelShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 9:
      Receive<fleetmap_msgs::msg::dds_::RobotFrame_PubSubType>(
          RobotFrameShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    case 10:
      Receive<fleetmap_msgs::msg::dds_::RouteGraph_PubSubType>(
          RouteGraphShape(), bytes, [](const auto& sample) { (void)FromIdl(sample); });
      break;
    default:
      Receive<tf2_msgs::msg::dds_::TFMessage_PubSubType>(
          TfMessageShape(), bytes, [](const auto& sample) {
            for (const auto& stamped : sample.transforms()) {
              (void)FromIdl(stamped.header().stamp());
            }
          });
      break;
  }
  return 0;
}
