#pragma once

// Internal to transport: the DDS content filter of class FLEETMAP_TILE_REGION a shard's server
// reads robot tiles through; what it passes: tile_region_selection.hpp.

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

#include <optional>
#include <string_view>

#include "common/core/ids.hpp"
#include "common/transport/tile_region_selection.hpp"

namespace fleetmap::transport {

// The factory every Participant registers under kTileRegionFilterClass; process-wide, never
// deleted (Fast DDS keeps the pointer for the participants' lifetime).
eprosima::fastdds::dds::IContentFilterFactory& TileRegionFilterFactory();

// The key a VectorTile sample starts with: robot_id, tile_x, tile_y (CDR, either endianness), or
// nullopt when the payload is too short for them.
struct TileSampleKey {
  std::string_view robot;
  TileId tile;
};
std::optional<TileSampleKey> ReadTileSampleKey(
    const eprosima::fastrtps::rtps::SerializedPayload_t& payload);

}  // namespace fleetmap::transport
