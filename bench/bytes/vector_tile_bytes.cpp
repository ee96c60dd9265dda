#include "bench/bytes/vector_tile_bytes.hpp"

#include <chrono>
#include <string>

#include "common/transport/tile_payload.hpp"
#include "common/transport/vector_tile_message.hpp"

namespace fleetmap::bench {

StatusOr<VectorTileBytes> MeasureVectorTileBytes(const vector_map::TiledVectorMap& map,
                                                 const RobotId& robot) {
  VectorTileBytes bytes;
  for (const auto& [tile, geometry] : map.tiles) {
    transport::VectorTileMessage message;
    message.robot_id = robot;
    message.tile = tile;
    message.revision = 1;
    // Fixed-width fields: any stamp gives the same bytes; a fixed one keeps runs identical.
    message.stamp = Timestamp(std::chrono::seconds(1700000000));
    message.tile_size = map.tile_size;
    message.map = geometry;
    StatusOr<std::string> payload = transport::EncodeTilePayload(message);
    if (!payload.ok()) {
      return payload.status().WithContext("tile (" + std::to_string(tile.x) + ", " +
                                          std::to_string(tile.y) + ")");
    }
    bytes.payload += payload->size();
    ++bytes.tiles;
  }
  return bytes;
}

}  // namespace fleetmap::bench
