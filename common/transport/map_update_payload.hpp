#pragma once

// One map_msgs/OccupancyGridUpdate as bytes: the CDR encoding of the sample (with the
// encapsulation header), as a ROS 2 SLAM node puts a patch of its map on rt/<map>_updates. The lab
// counts these bytes as the grid baseline of a tile (bench/bytes/grid_tile_bytes.hpp).

#include <string>

#include "common/transport/map_message.hpp"

namespace fleetmap::transport {

// `update.data` must hold width x height cells (a broken invariant otherwise). `frame_id` goes in
// the header, as ROS 2 fills it ("map"); MapUpdate itself does not carry one.
std::string EncodeMapUpdatePayload(const MapUpdate& update, const std::string& frame_id);

}  // namespace fleetmap::transport
