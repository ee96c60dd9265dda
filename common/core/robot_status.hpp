#pragma once

#include <cstdint>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"

namespace fleetmap {

// What the map changes an agent published would have cost on the ROS-native grid wires, in
// payload bytes (encapsulation + CDR) summed over the changes: a whole nav_msgs/OccupancyGrid per
// change, or one map_msgs/OccupancyGridUpdate per changed fleet tile, raw or compressed.
struct WireBaselines {
  uint64_t events = 0;  // map changes accounted for
  uint64_t grid_bytes = 0;
  uint64_t patch_bytes = 0;
  uint64_t zstd3_bytes = 0;
  uint64_t zstd19_bytes = 0;
  uint64_t lz4_bytes = 0;
  uint32_t patches_pending = 0;  // still being compressed: the figures are not final yet
};

// What an agent reports about its robot: where it is, where its map sits in the fleet frame,
// what it has published. Plain data; the wire form is fleetmap_msgs/msg/RobotStatus.
struct RobotStatus {
  RobotId robot;
  Timestamp stamp;
  Pose2 map_from_robot;
  Pose2 fleet_from_map;
  std::string map_topic;
  uint32_t map_width = 0;
  uint32_t map_height = 0;
  double map_resolution = 0.0;
  uint32_t map_revision = 0;
  uint64_t maps_published = 0;
  uint64_t tiles_published = 0;
  uint64_t bytes_published = 0;
  uint32_t sequence_number = 0;
  WireBaselines baselines;  // with --measure-baselines only
  // The agent does not know where its map frame sits (--unplaced): its tiles are in its own map
  // frame, the server places them, and fleet_from_map is the placement learned from
  // rt/fleetmap/robot_frames (identity until then).
  bool tiles_in_map_frame = false;
  // fleet_from_map was given to the agent and is the robot's frame (with tiles_in_map_frame: the
  // server carries the map-frame tiles into the fleet frame at it, any rotation included).
  bool fleet_from_map_given = false;
};

}  // namespace fleetmap
