#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "common/core/options_printer.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/core/wire.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "robot_agent/entity_publisher.hpp"
#include "robot_agent/grid_wire_publisher.hpp"
#include "robot_agent/id_claim_watch.hpp"
#include "robot_agent/map_source.hpp"
#include "robot_agent/server_watch.hpp"
#include "robot_agent/sim_map_source.hpp"
#include "robot_agent/status_heartbeat.hpp"
#include "robot_agent/tile_publisher.hpp"
#include "robot_agent/wire_baseline_meter.hpp"

namespace fleetmap::agent {

struct AgentOptions {
  RobotId robot;
  std::string map_path;           // a ROS map_server YAML (re-read when it changes), or
  std::string ros_topic;          // a DDS topic carrying nav_msgs/OccupancyGrid, e.g. rt/map, or
  std::optional<SimOptions> sim;  // the built-in simulated robot
  // An entities JSON file (doors, stairs, people's tracks; docs/extrapolation.md) the robot's
  // perception writes, re-read when it changes and published on rt/fleetmap/entities. Optional.
  std::string entities_path;
  // Size limits for the images of map_path (docs/file-formats.md, "Limits").
  grid::MapLoadOptions map_limits;
  Wire wire = Wire::kTiles;
  // With Wire::kTiles: also measure what the same map changes would have cost on the grid wires
  // (WireBaselineMeter), reported in the status. Costs idle CPU, and time when the agent stops.
  bool measure_baselines = false;
  TilePublisherOptions tiles;
  Pose2 fleet_from_map;  // where the robot's map frame sits in the fleet frame
  // The robot does not know fleet_from_map: its tiles are cut in its own map frame and the
  // server places them by registration; the agent learns its placement from
  // rt/fleetmap/robot_frames.
  bool unplaced = false;
  // Tiles and patches are cut on axis-aligned cells of the fleet frame, which a rotated map frame
  // does not have: such a robot cuts them in its own map frame and the server carries them into
  // the fleet frame at its given fleet_from_map (exactly as it does for a robot it placed).
  bool TilesInMapFrame() const { return unplaced || std::abs(fleet_from_map.yaw) > 0.0; }
  // The frame tiles are cut in: the fleet frame, or the robot's own map frame.
  Pose2 TilingFrame() const { return TilesInMapFrame() ? Pose2{} : fleet_from_map; }
  Pose2 map_from_robot;                          // the robot's pose in its map frame
  std::chrono::milliseconds status_period{500};  // a quarter of the 2 s liveliness lease
  std::chrono::milliseconds map_check_period{200};
  std::chrono::milliseconds duration{0};  // run this long, then leave; 0: until stopped
  // How long the agent listens, before it joins, for another participant already speaking for
  // its robot id (DDS discovery on a LAN takes a few hundred milliseconds). 0: do not check.
  std::chrono::milliseconds claim_wait{1000};
  // Seen no fleet server this long (no writer of rt/fleetmap/fused_tiles), the agent says so.
  std::chrono::milliseconds server_wait{10'000};
  transport::ParticipantOptions dds;

  // Checks every field once; the error names the option and the value.
  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// fleetmap-agent's node: takes the robot's grid from its source, publishes the tiles that changed
// (or, on a grid wire, the grid or its changed patches: GridWirePublisher), its RobotStatus twice
// a second, watches for a fleet server and for its own frame,
// and leaves the fleet (disposes its status) when stopped. Run() on one thread; `stop` may be
// set from any thread.
class AgentNode {
 public:
  static StatusOr<std::unique_ptr<AgentNode>> Create(AgentOptions options);

  Status Run(const std::atomic<bool>& stop);

 private:
  explicit AgentNode(AgentOptions options) : options_(std::move(options)) {}

  // A new grid from the source: publish what changed.
  Status OnNewMap(const grid::OccupancyGrid& map);
  // Hands what the status says now (map, pose, byte accounting) to the heartbeat.
  void RefreshStatus();
  // Learns the robot's map frame from rt/fleetmap/robot_frames.
  void DrainRobotFrames();
  // Says when no fleet server has been in sight for options_.server_wait, and when one is again.
  void WatchServer(std::chrono::steady_clock::time_point now);
  // Another participant that starts claiming this robot id once the agent is in the fleet is
  // reported: the server keeps this agent and refuses the other.
  void WatchIdClaims();
  // Secured: logs once how long the DDS Security handshake with the server took.
  void ReportHandshake();
  // Lets the byte accounting finish, still reporting the robot alive, and reports its totals.
  void FinishBaselines();

  AgentOptions options_;
  RobotStatus status_;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<MapSource> source_;
  SimMapSource* sim_source_ = nullptr;  // source_, when it is the simulator (for the pose)
  std::unique_ptr<transport::RobotStatusWriter> status_writer_;
  std::unique_ptr<StatusHeartbeat> heartbeat_;         // publishes status_ from its own thread
  std::unique_ptr<GridWirePublisher> grid_publisher_;  // a grid wire
  std::unique_ptr<TilePublisher> tile_publisher_;      // Wire::kTiles
  std::unique_ptr<WireBaselineMeter> baseline_meter_;  // with measure_baselines
  std::unique_ptr<transport::RobotFrameReader> frame_reader_;
  std::unique_ptr<EntityPublisher> entity_publisher_;  // with entities_path
  std::unique_ptr<IdClaimWatch> claim_watch_;
  std::optional<ServerWatch> server_watch_;  // from Run() on
  bool placed_ = false;  // with unplaced: the server has placed the robot's map frame
  bool handshake_reported_ = false;
};

}  // namespace fleetmap::agent
