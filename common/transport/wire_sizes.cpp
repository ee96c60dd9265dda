#include "common/transport/wire_sizes.hpp"

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/conversions.hpp"

namespace fleetmap::transport {

size_t OccupancyGridPayloadBytes(const MapMessage& message) { return PayloadBytes(ToIdl(message)); }

size_t MapUpdatePayloadBytes(const MapUpdate& update) { return PayloadBytes(ToIdl(update)); }

size_t CompressedMapUpdatePayloadBytes(const CompressedMapUpdate& update) {
  return PayloadBytes(ToIdl(update));
}

}  // namespace fleetmap::transport
