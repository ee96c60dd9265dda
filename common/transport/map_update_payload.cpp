#include "common/transport/map_update_payload.hpp"

#include "common/core/check.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/conversions.hpp"

namespace fleetmap::transport {

std::string EncodeMapUpdatePayload(const MapUpdate& update, const std::string& frame_id) {
  FLEETMAP_CHECK(update.width >= 0 && update.height >= 0 &&
                     update.data.size() == static_cast<size_t>(update.width) * update.height,
                 "a map update's data must hold width x height cells");
  map_msgs::msg::dds_::OccupancyGridUpdate_ sample = ToIdl(update);
  sample.header().frame_id(frame_id);
  return SerializeCdr(sample);
}

}  // namespace fleetmap::transport
