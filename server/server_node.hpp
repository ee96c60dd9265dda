#pragma once

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/wake_up.hpp"

namespace fleetmap::server {

struct ServerOptions {
  std::chrono::milliseconds duration{0};  // run this long; 0: until stopped
  transport::ParticipantOptions dds;

  Status Validate() const;
};

// What the server knows of one robot.
struct RobotRecord {
  enum class State { kActive, kLeft, kLost };
  State state = State::kActive;
  RobotStatus last_status;
  std::optional<transport::MapMessage> latest_map;
  uint64_t maps_received = 0;
  uint64_t bytes_received = 0;
  uint64_t rejected_samples = 0;
  std::unique_ptr<transport::OccupancyGridReader> map_reader;  // while the robot is active
};

const char* RobotStateName(RobotRecord::State state);

// fleetmap-server's node: follows the fleet on rt/fleetmap/robot_status, subscribes to each
// robot's rt/<robot>/map while it is in the fleet and keeps its latest map. A malformed sample
// from one robot is logged and dropped; it never stops the server. All work happens on the
// thread that calls Run(); DDS listeners only queue samples. `stop` may be set from any thread.
class ServerNode {
 public:
  static StatusOr<std::unique_ptr<ServerNode>> Create(ServerOptions options);

  Status Run(const std::atomic<bool>& stop);

  // Read after Run() returns (or from the Run() thread).
  const std::map<RobotId, RobotRecord>& robots() const { return robots_; }

 private:
  explicit ServerNode(ServerOptions options) : options_(std::move(options)) {}

  void HandleRobotEvents();
  void OnRobotAlive(const RobotStatus& status);
  void OnRobotGone(const RobotId& robot, RobotRecord::State state);
  void HandleMaps();
  void PrintSummary() const;

  ServerOptions options_;
  std::shared_ptr<transport::WakeUp> wake_up_ = std::make_shared<transport::WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::RobotStatusReader> status_reader_;
  std::map<RobotId, RobotRecord> robots_;
};

}  // namespace fleetmap::server
