#pragma once

// DDS topic names. ROS 2 maps a topic /a/b to the DDS topic rt/a/b, so ROS 2 tools see these as
// /fleetmap/robot_status, /<robot>/map and so on. docs/topics.md lists type, key and QoS of each.

#include <string>

#include "common/core/ids.hpp"

namespace fleetmap::transport {

inline constexpr char kRobotStatusTopic[] = "rt/fleetmap/robot_status";
inline constexpr char kRobotTilesTopic[] = "rt/fleetmap/robot_tiles";
inline constexpr char kFusedTilesTopic[] = "rt/fleetmap/fused_tiles";
inline constexpr char kFleetMapTopic[] = "rt/fleetmap/map";
inline constexpr char kEntitiesTopic[] = "rt/fleetmap/entities";
inline constexpr char kSubmapGraphTopic[] = "rt/fleetmap/submap_graph";
inline constexpr char kObjectTemplatesTopic[] = "rt/fleetmap/object_templates";
inline constexpr char kObjectsTopic[] = "rt/fleetmap/objects";
inline constexpr char kRobotFramesTopic[] = "rt/fleetmap/robot_frames";
inline constexpr char kAdmissionsTopic[] = "rt/fleetmap/admissions";
inline constexpr char kServersTopic[] = "rt/fleetmap/servers";
inline constexpr char kRouteGraphTopic[] = "rt/fleetmap/route_graph";
// A shard's fused grid of its own region (docs/shards.md): /fleetmap/<shard>/map to ROS 2 tools.
inline std::string ShardMapTopic(const std::string& shard) {
  return "rt/fleetmap/" + shard + "/map";
}
// ROS 2's transform tree (/tf): the server publishes fleet -> <robot>/map there.
inline constexpr char kTfTopic[] = "rt/tf";

// Where a robot publishes its own grid: what a ROS 2 robot named `robot` publishes as /<robot>/map.
inline std::string RobotMapTopic(const RobotId& robot) { return "rt/" + robot.value + "/map"; }
// Where an agent on the patch wire publishes map_msgs/OccupancyGridUpdate patches of that grid
// (/<robot>/map_updates, ROS's name for the updates of /<robot>/map), and their zstd twins
// (fleetmap_msgs/CompressedGridUpdate).
inline std::string RobotMapUpdatesTopic(const RobotId& robot) {
  return RobotMapTopic(robot).append("_updates");
}
inline std::string RobotCompressedMapUpdatesTopic(const RobotId& robot) {
  return RobotMapTopic(robot).append("_updates_zstd");
}

}  // namespace fleetmap::transport
