#pragma once

// What a sample would take on the wire without writing it: its payload bytes (the 4-byte
// encapsulation header and the CDR the generated type support writes), counted as every writer
// counts what it publishes. For byte accounting of wires that are not running (the agent's
// --measure-baselines), so the figures are those of the real serializer, never an estimate.

#include <cstddef>

#include "common/transport/map_message.hpp"
#include "common/transport/map_update_codec.hpp"

namespace fleetmap::transport {

size_t OccupancyGridPayloadBytes(const MapMessage& message);
size_t MapUpdatePayloadBytes(const MapUpdate& update);
size_t CompressedMapUpdatePayloadBytes(const CompressedMapUpdate& update);

}  // namespace fleetmap::transport
