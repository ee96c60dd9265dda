#pragma once

// The vector-tile codec: a VectorTileMessage to and from a fleetmap_msgs/VectorTile, in layout 5
// of docs/file-formats.md ("VectorTile, field by field"): vertices as varint steps of the tile
// lattice, each relative to the vertex before it, in one byte string that is zstd-compressed when
// that makes it smaller. Internal to transport; the writers and readers of the tile topics, tile
// payloads and .vmap files use it. The plain ROS messages' conversions are in conversions.hpp.

#include "common/core/status.hpp"
#include "common/transport/vector_tile_message.hpp"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::transport {

// Codes the tile's geometry on the map's lattice (VectorMap::lattice; a map without one gets
// vector_map::TileQuantum(resolution) from the fleet origin, and its vertices are
// rounded onto it). Fails (kInvalidArgument) when the lattice quantum does not divide the tile side
// into at most 65535 steps, when the tile side is not a whole number of millimetres, when a
// coordinate or the tile size is not finite, when a vertex lies too far outside its tile or a half
// width is not within epsilon.
StatusOr<fleetmap_msgs::msg::dds_::VectorTile_> ToIdl(const VectorTileMessage& message);
// Checks every field, length, count and coordinate before it trusts it: a malformed tile is an
// error naming what is wrong, never a crash or an allocation the bytes cannot pay for. The map
// comes back as it was given to ToIdl (on the lattice it was sent on), except that obstacles come
// in the order polylines, then point obstacles, and a closed polyline of fewer than 3 vertices
// comes back open (the same segments). `limits` bound what the tile may decode to; they are
// checked before the memory is allocated; a tile past them is kResourceExhausted.
StatusOr<VectorTileMessage> FromIdl(const fleetmap_msgs::msg::dds_::VectorTile_& tile,
                                    const TileDecodeLimits& limits = {});

}  // namespace fleetmap::transport
