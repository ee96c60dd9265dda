#include "common/transport/map_update_writer.hpp"

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

Status MapUpdateWriter::Write(const MapUpdate& update) {
  auto sample = ToIdl(update);
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write a map update on " + endpoint_->topic_name());
  }
  return Status::Ok();
}

}  // namespace fleetmap::transport
