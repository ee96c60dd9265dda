#include "common/transport/occupancy_grid_writer.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "nav_msgs/msg/OccupancyGrid.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;

StatusOr<std::unique_ptr<OccupancyGridWriter>> OccupancyGridWriter::Create(
    Participant& participant, const std::string& topic_name) {
  std::unique_ptr<OccupancyGridWriter> self(new OccupancyGridWriter());
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_, WriterEndpoint::Create(participant, topic_name, OccupancyGridTypeSupport(),
                                              OccupancyGridQos().writer));
  return self;
}

OccupancyGridWriter::~OccupancyGridWriter() = default;

StatusOr<size_t> OccupancyGridWriter::Write(const MapMessage& message) {
  auto sample = ToIdl(message);
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write the map on " + endpoint_->topic_name());
  }
  return PayloadBytes(sample);
}

int OccupancyGridWriter::matched_readers() const {
  dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.current_count;
}

}  // namespace fleetmap::transport
