#include "common/transport/map_update_writer.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "common/transport/internal/cdr_codec.hpp"

#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"

namespace fleetmap::transport {

StatusOr<std::unique_ptr<MapUpdateWriter>> MapUpdateWriter::Create(Participant& participant,
                                                                   const std::string& topic_name) {
  std::unique_ptr<MapUpdateWriter> self(new MapUpdateWriter());
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      WriterEndpoint::Create(participant, topic_name, OccupancyGridUpdateTypeSupport(),
                             OccupancyGridUpdateQos().writer));
  return self;
}

MapUpdateWriter::~MapUpdateWriter() = default;

StatusOr<size_t> MapUpdateWriter::Write(const MapUpdate& update) {
  auto sample = ToIdl(update);
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write a map update on " + endpoint_->topic_name());
  }
  return PayloadBytes(sample);
}

int MapUpdateWriter::matched_readers() const {
  eprosima::fastdds::dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.current_count;
}

int MapUpdateWriter::readers_ever_matched() const {
  eprosima::fastdds::dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.total_count;
}

}  // namespace fleetmap::transport
