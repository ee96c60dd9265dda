#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_writer.hpp"

namespace fleetmap::agent {

struct AgentOptions {
  RobotId robot;
  std::string map_path;  // a ROS map_server YAML
  Pose2 fleet_from_map;  // where the robot's map frame sits in the fleet frame
  Pose2 map_from_robot;  // the robot's pose in its map frame
  std::chrono::milliseconds status_period{500};
  std::chrono::milliseconds map_check_period{1000};  // how often the map file is checked for change
  std::chrono::milliseconds duration{0};             // run this long, then leave; 0: until stopped
  transport::ParticipantOptions dds;

  // Checks every field once; the error names the option and the value.
  Status Validate() const;
};

// fleetmap-agent's node: publishes the robot's map as nav_msgs/OccupancyGrid on rt/<robot>/map
// (again whenever the map file changes) and its RobotStatus twice a second; leaves the fleet
// (disposes its status) when stopped. Run() on one thread; `stop` may be set from any thread.
class AgentNode {
 public:
  static StatusOr<std::unique_ptr<AgentNode>> Create(AgentOptions options);

  Status Run(const std::atomic<bool>& stop);

 private:
  explicit AgentNode(AgentOptions options) : options_(std::move(options)) {}

  Status LoadMap();
  Status PublishMap();
  Status PublishStatus();
  // Reloads and republishes the map if its file changed; a broken file keeps the old map.
  void ReloadMapIfChanged();

  AgentOptions options_;
  grid::OccupancyGrid map_;
  std::filesystem::file_time_type map_mtime_;
  RobotStatus status_;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::RobotStatusWriter> status_writer_;
  std::unique_ptr<transport::OccupancyGridWriter> map_writer_;
};

}  // namespace fleetmap::agent
