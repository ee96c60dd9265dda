#pragma once

// The vector-tile codec: a VectorTileMessage to and from a fleetmap_msgs/VectorTile, in the
// quantised layout of docs/file-formats.md ("VectorTile, field by field"). Internal to transport;
// the writers and readers of the tile topics, tile payloads and .vmap files use it. The plain ROS
// messages' conversions are in conversions.hpp.

#include "common/core/status.hpp"
#include "common/transport/vector_tile_message.hpp"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::transport {

// Quantises the tile's geometry to int16 multiples of TileQuantum(tile_size) from the tile's
// corner (the layout is in docs/file-formats.md). One-vertex polylines go to the point arrays; a
// closed polyline repeats its first vertex at its end; a polyline of more than 65535 wire vertices
// is split into open pieces that share their end vertices. Fails (kInvalidArgument) when a vertex
// is too far outside its tile for int16, when a coordinate or the tile size is not finite, when a
// half width does not fit, or when a free ring has more than 65535 vertices or a free polygon
// more than 65535 rings.
StatusOr<fleetmap_msgs::msg::dds_::VectorTile_> ToIdl(const VectorTileMessage& message);
// Checks that every count adds up and every number is sane before building the tile. The map
// comes back as it was given to ToIdl, except that obstacles come in the order polylines, then
// point obstacles; a closed polyline of fewer than 3 vertices comes back open, and an open one of
// n >= 4 vertices whose last vertex is its first comes back closed without that last vertex
// (the same segments either way); split polylines come back as their pieces.
StatusOr<VectorTileMessage> FromIdl(const fleetmap_msgs::msg::dds_::VectorTile_& tile);

}  // namespace fleetmap::transport
