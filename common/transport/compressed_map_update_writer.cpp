#include "common/transport/compressed_map_update_writer.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"

namespace fleetmap::transport {

StatusOr<std::unique_ptr<CompressedMapUpdateWriter>> CompressedMapUpdateWriter::Create(
    Participant& participant, const std::string& topic_name) {
  std::unique_ptr<CompressedMapUpdateWriter> self(new CompressedMapUpdateWriter());
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      WriterEndpoint::Create(participant, topic_name, CompressedGridUpdateTypeSupport(),
                             OccupancyGridUpdateQos().writer));
  return self;
}

CompressedMapUpdateWriter::~CompressedMapUpdateWriter() = default;

StatusOr<size_t> CompressedMapUpdateWriter::Write(const CompressedMapUpdate& update) {
  auto sample = ToIdl(update);
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write a compressed map update on " +
                            endpoint_->topic_name());
  }
  return PayloadBytes(sample);
}

int CompressedMapUpdateWriter::readers_ever_matched() const {
  eprosima::fastdds::dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.total_count;
}

}  // namespace fleetmap::transport
