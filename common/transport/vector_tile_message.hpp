#pragma once

#include "common/vector_map/vector_tile.hpp"

namespace fleetmap::transport {

// One tile as it travels in a fleetmap_msgs/VectorTile: the plain vector tile, as it is.
using VectorTileMessage = vector_map::VectorTile;
using TileDecodeLimits = vector_map::TileDecodeLimits;

}  // namespace fleetmap::transport
