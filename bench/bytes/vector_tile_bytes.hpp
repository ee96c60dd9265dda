#pragma once

// The bytes of a tiled vector map as the fleet's wire carries it: each tile as the
// fleetmap_msgs/VectorTile sample a robot agent publishes on rt/fleetmap/robot_tiles, encoded by
// transport::EncodeTilePayload (the real encoder, so the figures follow the tile layout), summed
// over the tiles. The counterpart of grid_tile_bytes.hpp. Not a test. Any thread.

#include <cstddef>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::bench {

// A robot id as the simulated fleet names its robots: the sample carries it, so its length counts.
inline const RobotId kBenchRobot{"robot0"};

struct VectorTileBytes {
  size_t tiles = 0;
  size_t payload = 0;  // summed VectorTile samples, encapsulation header included
};

// Every tile of `map` as robot `robot`'s first revision of it. Errors: a tile the encoder refuses
// (named).
StatusOr<VectorTileBytes> MeasureVectorTileBytes(const vector_map::TiledVectorMap& map,
                                                 const RobotId& robot = kBenchRobot);

}  // namespace fleetmap::bench
