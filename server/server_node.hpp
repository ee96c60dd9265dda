#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "server/fleet_presence.hpp"
#include "server/fusion_worker.hpp"
#include "server/object_learning_worker.hpp"
#include "server/prediction_worker.hpp"
#include "server/refusal_log.hpp"
#include "server/robot_map_feed.hpp"
#include "server/robot_registry.hpp"
#include "server/route_graph_worker.hpp"

namespace fleetmap::server {

struct ServerOptions {
  std::chrono::milliseconds duration{0};  // run this long; 0: until stopped
  transport::ParticipantOptions dds;
  fusion::FleetMapOptions map;  // what the fleet map fuses, admits and places
  FusionWorkerOptions worker;   // how the fusion worker keeps, publishes and waits
  ObjectLearningOptions learning;
  extrapolation::PredictionOptions prediction;
  RouteGraphServiceOptions route_graph;  // the fused map as a route graph (off by default)
  // Known fleet_from_map per robot (--transforms): used for grid-wire robots instead of what
  // their status says; a tile-wire robot whose status disagrees is reported.
  std::map<RobotId, Pose2> transforms;
  // Robot ids one DDS participant may speak for (an agent speaks for one; a simulation for a few).
  size_t max_robots_per_participant = 16;
  // How other servers, the view and the log name this server; empty: host:pid.
  std::string name;
  // Of the live servers on the domain, the strongest serves the fleet (docs/standby.md); a hot
  // standby gets a lower strength.
  int32_t ownership_strength = 100;
  // A shard's server (--shard, docs/shards.md): it fuses its region's tiles, and ranks among
  // its shard's servers only.
  std::optional<ShardAssignment> shard;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What the server knows of one robot.
struct RobotRecord {
  enum class State { kActive, kLeft, kLost };
  State state = State::kActive;
  RobotStatus last_status;
  uint64_t maps_received = 0;     // whole maps (grid wires)
  uint64_t updates_received = 0;  // map updates applied (patch wires)
  uint64_t bytes_received = 0;
  uint64_t rejected_samples = 0;
  uint64_t id_clashes = 0;  // status samples from a second agent claiming this robot id
  bool transform_mismatch_reported = false;
  // While a robot on a grid wire is active: its rt/<robot>/map (and patches).
  std::unique_ptr<RobotMapFeed> map_feed;
};

const char* RobotStateName(RobotRecord::State state);

// fleetmap-server's node: follows the fleet on rt/fleetmap/robot_status (joins, departures,
// deaths, two agents claiming one id) and runs the FusionWorker that fuses every robot's tiles
// and redistributes the fused map, the ObjectLearningWorker that learns movable objects from the
// finished mapping sessions, and the PredictionWorker that turns the entities robots recognise
// (rt/fleetmap/entities, taken here to the fleet frame) into the sub-map graph. Robots on a grid
// wire are read on rt/<robot>/map, patched by their updates on a patch wire (RobotMapFeed), and
// their grids fused too. A robot that leaves keeps its
// contribution. A malformed sample from one robot is logged, counted and dropped; it never stops
// the server. The control work happens on the thread that calls Run(), fusion on the worker's; DDS
// listeners only queue samples. `stop` may be set from any thread.
class ServerNode {
 public:
  static StatusOr<std::unique_ptr<ServerNode>> Create(ServerOptions options);

  Status Run(const std::atomic<bool>& stop);

  // Read after Run() returns (or from the Run() thread).
  const std::map<RobotId, RobotRecord>& robots() const { return robots_; }

 private:
  explicit ServerNode(ServerOptions options) : options_(std::move(options)) {}

  void HandleRobotEvents();
  void OnRobotAlive(const RobotStatus& status, const std::string& writer);
  // `writer` sent the disposal or lost its liveliness: only the robot's owner ends it.
  void OnRobotGone(const RobotId& robot, RobotRecord::State state, const std::string& writer);
  // Where the robot's map frame sits in the fleet: the configured transform, else its own word;
  // for a robot that does not know it, where the server placed it (nullopt: not yet).
  std::optional<Pose2> FleetFromMap(const RobotRecord& record) const;
  // The frame given for the robot (the server's transforms file, else its agent's
  // --fleet-from-map); nullopt when the server places it.
  std::optional<Pose2> GivenFrame(const RobotRecord& record) const;
  // Entities of robots that were not placed when they came, once their robot is.
  void SubmitEntitiesOfPlacedRobots();
  void HandleMaps();
  void HandleEntities();
  // Hands an entity of a known robot to the prediction worker, in the fleet frame.
  void SubmitEntity(transport::EntityMessage entity, const RobotRecord& record);
  void PrintSummary(const FusionStats& fusion) const;
  // options_.name, else host:pid.
  std::string ServerName() const;
  // What rt/fleetmap/servers says of the shard it fuses (empty, zeros: unsharded).
  std::string ShardName() const;
  std::array<double, 4> ShardRegion() const;

  ServerOptions options_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  // The robots' statuses and liveliness come in on a participant of their own: its own ports,
  // receive threads and event thread, so that a flood of tiles (however many writers send them)
  // cannot delay the liveliness of the robots and get honest robots reported lost.
  std::unique_ptr<transport::Participant> status_participant_;
  std::unique_ptr<transport::RobotStatusReader> status_reader_;
  std::shared_ptr<RobotRegistry> registry_;
  std::unique_ptr<FusionWorker> fusion_worker_;
  // Before the workers that tell it sub-maps and objects: destroyed after them.
  std::unique_ptr<RouteGraphWorker> route_graph_worker_;    // null when disabled
  std::unique_ptr<ObjectLearningWorker> learning_worker_;   // null when disabled
  std::unique_ptr<PredictionWorker> prediction_worker_;     // null when disabled
  std::unique_ptr<transport::EntityReader> entity_reader_;  // null when prediction is disabled
  // Entities of robots whose status (and so fleet_from_map) has not arrived yet, by robot, with
  // the writer that sent each: only the owner's are used once a status claims the robot.
  static constexpr size_t kMaxEarlyRobots = 64;
  std::map<RobotId, std::vector<std::pair<std::string, transport::EntityMessage>>> early_entities_;
  static constexpr size_t kMaxEntitiesAwaitingPlacement = 1024;  // per robot
  std::map<RobotId, std::vector<transport::EntityMessage>> awaiting_placement_;
  // Among the fleet's servers: whether this one serves.
  std::unique_ptr<FleetPresence> presence_;
  RefusalLog refusals_{"server"};
  uint64_t rejected_entities_ = 0;
  std::map<RobotId, RobotRecord> robots_;
};

}  // namespace fleetmap::server
