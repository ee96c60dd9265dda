#pragma once

#include <cstdint>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"

namespace fleetmap {

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
};

}  // namespace fleetmap
