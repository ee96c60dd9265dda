#pragma once

// One vector tile as bytes: the CDR encoding of its fleetmap_msgs/VectorTile sample (with the
// encapsulation header), exactly what travels on rt/fleetmap/robot_tiles. The server's map store
// keeps tiles in this form, so a stored tile and a received one are the same bytes.

#include <string>
#include <string_view>

#include "common/core/status.hpp"
#include "common/transport/vector_tile_message.hpp"

namespace fleetmap::transport {

StatusOr<std::string> EncodeTilePayload(const VectorTileMessage& tile);
// Checks lengths before decoding and every count after; `name` prefixes errors.
StatusOr<VectorTileMessage> DecodeTilePayload(std::string_view bytes, const std::string& name,
                                              const TileDecodeLimits& limits = {});

}  // namespace fleetmap::transport
