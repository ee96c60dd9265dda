#include "common/transport/vector_tile_writer.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/topics.hpp"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using fleetmap_msgs::msg::dds_::VectorTile_;

StatusOr<std::unique_ptr<VectorTileWriter>> VectorTileWriter::Create(
    Participant& participant, const std::string& topic_name) {
  std::unique_ptr<VectorTileWriter> self(new VectorTileWriter());
  // The fused tiles are state a server serves (served_state.hpp); a robot's are its own.
  const EndpointQos qos = topic_name == kFusedTilesTopic
                              ? ServedStateQos(participant.ownership_strength())
                              : VectorTileQos();
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      WriterEndpoint::Create(participant, topic_name, VectorTileTypeSupport(), qos.writer));
  return self;
}

VectorTileWriter::~VectorTileWriter() = default;

StatusOr<size_t> VectorTileWriter::Write(const VectorTileMessage& message) {
  FLEETMAP_ASSIGN_OR_RETURN(VectorTile_ sample, ToIdl(message));
  if (!endpoint_->Write(&sample)) {
    return UnavailableError("could not write a vector tile on " + endpoint_->topic_name());
  }
  return PayloadBytes(sample);
}

Status VectorTileWriter::Dispose(const RobotId& robot_id, const TileId& tile) {
  VectorTile_ key;
  key.robot_id(robot_id.value);
  key.tile_x(tile.x);
  key.tile_y(tile.y);
  if (!endpoint_->Dispose(&key)) {
    return UnavailableError("could not dispose a vector tile on " + endpoint_->topic_name());
  }
  return Status::Ok();
}

int VectorTileWriter::matched_readers() const {
  dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.current_count;
}

}  // namespace fleetmap::transport
