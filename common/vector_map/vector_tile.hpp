#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

// One tile of a robot's or the fleet's map: whose it is, where, which revision, and its geometry
// (vertices on the tile lattice, see tiled_vector_map.hpp). What travels in a
// fleetmap_msgs/VectorTile (transport::VectorTileMessage), what fusion takes in, and what the
// store keeps.
struct VectorTile {
  RobotId robot_id;  // "fleet" for fused tiles; empty in .vmap files
  TileId tile;
  uint32_t revision = 0;
  Timestamp stamp;
  double tile_size = 10.0;
  VectorMap map;
};

// How much one received tile may decode to. A reader checks each limit while it decodes, before
// it allocates what the bytes ask for: a zstd frame whose stated size exceeds max_geometry_bytes
// is refused before it is inflated, and a count that would take the tile past max_vertices or
// max_rings before anything is reserved. The defaults only bound what any tile may hold (files
// and stores); the server passes its admission's per-tile limits.
struct TileDecodeLimits {
  size_t max_geometry_bytes = size_t{4} << 20;  // the geometry, decompressed
  size_t max_vertices = std::numeric_limits<size_t>::max();
  size_t max_rings = std::numeric_limits<size_t>::max();  // free outer rings and holes
};

}  // namespace fleetmap::vector_map
