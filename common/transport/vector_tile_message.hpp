#pragma once

#include <cstdint>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::transport {

// One tile as it travels in a fleetmap_msgs/VectorTile: whose it is, where, which revision, and
// its geometry in the fleet frame (vertices on the tile lattice, see tiled_vector_map.hpp).
struct VectorTileMessage {
  RobotId robot_id;  // "fleet" for fused tiles; empty in .vmap files
  TileId tile;
  uint32_t revision = 0;
  Timestamp stamp;
  double tile_size = 10.0;
  vector_map::VectorMap map;
};

}  // namespace fleetmap::transport
