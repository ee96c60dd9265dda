#include "robot_agent/agent_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <thread>

#include "common/transport/topics.hpp"

namespace fleetmap::agent {
Status AgentOptions::Validate() const {
  if (!IsValidRobotName(robot.value)) {
    return InvalidArgumentError("--robot-id \"" + robot.value +
                                "\" is not a valid robot name ([A-Za-z][A-Za-z0-9_]*, <= 64)");
  }
  if (static_cast<int>(!map_path.empty()) + static_cast<int>(!ros_topic.empty()) +
          static_cast<int>(sim.has_value()) !=
      1) {
    return InvalidArgumentError(
        "give exactly one map source: --map FILE, --ros-topic TOPIC or --sim KIND");
  }
  if (sim) FLEETMAP_RETURN_IF_ERROR(sim->Validate());
  if (!ros_topic.empty() && ros_topic.rfind("rt/", 0) != 0) {
    return InvalidArgumentError("--ros-topic \"" + ros_topic +
                                "\" is not a DDS topic of a ROS 2 topic (it starts with rt/)");
  }
  if (!fleet_from_map.finite()) return InvalidArgumentError("--fleet-from-map is not finite");
  if (!map_from_robot.finite()) return InvalidArgumentError("--pose is not finite");
  if (unplaced && !(fleet_from_map == Pose2{})) {
    return InvalidArgumentError(
        "--unplaced says the robot's fleet_from_map is not known: do not give one too");
  }
  if (measure_baselines && wire != Wire::kTiles) {
    return InvalidArgumentError(std::string("--measure-baselines measures the grid wires beside "
                                            "--wire tiles, not --wire ")
                                    .append(WireName(wire)));
  }
  FLEETMAP_RETURN_IF_ERROR(tiles.Validate());
  if (status_period.count() <= 0) return InvalidArgumentError("the status period must be > 0");
  if (map_check_period.count() <= 0)
    return InvalidArgumentError("the map check period must be > 0");
  if (duration.count() < 0) return InvalidArgumentError("--duration must be >= 0");
  if (claim_wait.count() < 0) return InvalidArgumentError("--claim-wait must be >= 0");
  if (server_wait.count() <= 0) return InvalidArgumentError("--server-wait must be > 0");
  if (map_limits.max_cells <= 0 || map_limits.max_decoded_bytes <= 0) {
    return InvalidArgumentError("--max-cells and --max-decoded-bytes must be > 0");
  }
  return Status::Ok();
}

StatusOr<std::unique_ptr<AgentNode>> AgentNode::Create(AgentOptions options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<AgentNode> node(new AgentNode(std::move(options)));
  const AgentOptions& o = node->options_;
  // A bad map file is the user's to fix: fail before touching DDS.
  if (!o.map_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(node->source_, FileMapSource::Create(o.map_path, o.map_limits));
  }
  if (o.sim) {
    FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<SimMapSource> sim, SimMapSource::Create(*o.sim));
    node->sim_source_ = sim.get();
    node->source_ = std::move(sim);
  }

  transport::ParticipantOptions dds = o.dds;
  dds.name = "fleetmap-agent/" + o.robot.value;
  FLEETMAP_ASSIGN_OR_RETURN(node->participant_, transport::Participant::Create(dds));
  if (!o.ros_topic.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(node->source_,
                              TopicMapSource::Create(*node->participant_, o.ros_topic));
  }
  FLEETMAP_ASSIGN_OR_RETURN(node->status_writer_,
                            transport::RobotStatusWriter::Create(*node->participant_));
  if (o.wire != Wire::kTiles) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->grid_publisher_,
        GridWirePublisher::Create(*node->participant_, o.robot, o.TilingFrame(), o.wire,
                                  o.tiles.tile_size));
  } else {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->tile_publisher_,
        TilePublisher::Create(*node->participant_, o.robot, o.TilingFrame(), o.tiles));
  }
  if (o.measure_baselines) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->baseline_meter_,
        WireBaselineMeter::Create(o.robot, o.TilingFrame(), o.tiles.tile_size));
  }
  // Its own frame only: a fleet's other robots' frames are no concern of this agent's.
  FLEETMAP_ASSIGN_OR_RETURN(node->frame_reader_, transport::RobotFrameReader::CreateForRobot(
                                                     *node->participant_, o.robot));
  if (!o.entities_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->entity_publisher_,
        EntityPublisher::Create(*node->participant_, o.robot, o.entities_path));
  }

  FLEETMAP_ASSIGN_OR_RETURN(node->claim_watch_, IdClaimWatch::Create(*node->participant_, o.robot));
  // Every endpoint is created, so discovery runs while the agent listens for a prior claim.
  FLEETMAP_RETURN_IF_ERROR(node->claim_watch_->CheckIdIsFree(o.claim_wait));

  RobotStatus& status = node->status_;
  status.robot = o.robot;
  status.fleet_from_map = o.fleet_from_map;
  status.tiles_in_map_frame = o.TilesInMapFrame();
  status.fleet_from_map_given = !o.unplaced;
  status.map_from_robot = o.map_from_robot;
  status.map_topic = node->grid_publisher_ != nullptr ? node->grid_publisher_->topic()
                                                      : std::string(transport::kRobotTilesTopic);
  return node;
}

Status AgentNode::OnNewMap(const grid::OccupancyGrid& map) {
  ++status_.map_revision;
  status_.map_width = static_cast<uint32_t>(map.width());
  status_.map_height = static_cast<uint32_t>(map.height());
  status_.map_resolution = map.resolution();
  if (grid_publisher_ != nullptr) {
    FLEETMAP_ASSIGN_OR_RETURN(const GridWirePublisher::Published published,
                              grid_publisher_->Publish(map));
    status_.maps_published = grid_publisher_->maps_published();
    status_.tiles_published = grid_publisher_->patches_published();
    status_.bytes_published = grid_publisher_->bytes_published();
    spdlog::info(
        "{}: published map revision {} ({} x {} cells) as {}, {} bytes on {}", options_.robot.value,
        status_.map_revision, map.width(), map.height(),
        published.whole_grid ? std::string("the whole grid")
                             : fmt::format("{} patches", published.patches),
        published.bytes,
        published.whole_grid ? transport::RobotMapTopic(options_.robot) : grid_publisher_->topic());
    return Status::Ok();
  }
  if (baseline_meter_ != nullptr) FLEETMAP_RETURN_IF_ERROR(baseline_meter_->Account(map));
  const uint64_t tiles_before = tile_publisher_->tiles_published();
  const uint64_t bytes_before = tile_publisher_->bytes_published();
  FLEETMAP_RETURN_IF_ERROR(tile_publisher_->Update(map));
  FLEETMAP_RETURN_IF_ERROR(tile_publisher_->Flush(std::chrono::steady_clock::now()));
  ++status_.maps_published;
  status_.tiles_published = tile_publisher_->tiles_published();
  status_.bytes_published = tile_publisher_->bytes_published();
  spdlog::info("{}: map revision {} ({} x {} cells): {} changed tiles, {} bytes{}",
               options_.robot.value, status_.map_revision, map.width(), map.height(),
               status_.tiles_published - tiles_before, status_.bytes_published - bytes_before,
               tile_publisher_->pending_tiles() > 0
                   ? fmt::format(" ({} waiting for bandwidth)", tile_publisher_->pending_tiles())
                   : std::string());
  return Status::Ok();
}

void AgentNode::RefreshStatus() {
  if (sim_source_ != nullptr) status_.map_from_robot = sim_source_->pose();
  if (baseline_meter_ != nullptr) status_.baselines = baseline_meter_->totals();
  heartbeat_->Update(status_);
}

void AgentNode::WatchIdClaims() {
  for (const std::string& other : claim_watch_->NewClaimants()) {
    spdlog::error(
        "{}: participant {} also claims robot id {}; the server keeps this agent (the first "
        "claim) and refuses the other",
        options_.robot.value, other, options_.robot.value);
  }
}

void AgentNode::WatchServer(std::chrono::steady_clock::time_point now) {
  // A server is seen by its fused-tile writer, as discovery reports it: the agent uses no fused
  // tile, so it does not read them (each of a large fleet's, or a flood's, would cost it CPU and
  // the server a send).
  const std::optional<std::string> said = server_watch_->Update(
      static_cast<int>(participant_->RemoteWritersOf(transport::kFusedTilesTopic)), now);
  if (!said) return;
  if (server_watch_->missing()) {
    spdlog::warn("{}: {}", options_.robot.value, *said);
  } else {
    spdlog::info("{}: {}", options_.robot.value, *said);
  }
}

void AgentNode::DrainRobotFrames() {
  for (const transport::RobotFrameEvent& event : frame_reader_->Drain()) {
    if (event.kind != transport::RobotFrameEvent::Kind::kSample ||
        event.message.robot != options_.robot) {
      continue;
    }
    const transport::RobotFrameMessage& frame = event.message;
    if (!options_.unplaced || !frame.placed()) continue;
    if (frame.fleet_from_map == status_.fleet_from_map && placed_) continue;
    placed_ = true;
    status_.fleet_from_map = frame.fleet_from_map;
    spdlog::info(
        "{}: this robot's map frame is at ({:.2f}, {:.2f}, {:.1f} deg) in the fleet "
        "frame ({} by the server, confidence {:.2f}, against {})",
        options_.robot.value, frame.fleet_from_map.x, frame.fleet_from_map.y,
        frame.fleet_from_map.yaw * 180.0 / M_PI, RobotFrameStateName(frame.state), frame.confidence,
        frame.placed_against.empty() ? "nothing: it anchors the fleet" : frame.placed_against);
  }
}

void AgentNode::ReportHandshake() {
  if (handshake_reported_ || !participant_->secured()) return;
  const std::optional<double> seconds = participant_->SecondsToAuthenticate("server");
  if (!seconds) return;
  handshake_reported_ = true;
  spdlog::info("{}: authenticated the server {:.2f} s after joining (DDS Security handshake)",
               options_.robot.value, *seconds);
}

Status AgentNode::Run(const std::atomic<bool>& stop) {
  if (auto first = source_->Poll()) FLEETMAP_RETURN_IF_ERROR(OnNewMap(*first));
  if (sim_source_ != nullptr) status_.map_from_robot = sim_source_->pose();
  heartbeat_ = std::make_unique<StatusHeartbeat>(*status_writer_, options_.status_period);
  FLEETMAP_RETURN_IF_ERROR(heartbeat_->Start(status_));
  if (entity_publisher_ != nullptr) FLEETMAP_RETURN_IF_ERROR(entity_publisher_->Poll());
  spdlog::info("{}: in the fleet on DDS domain {}{}, map from {}, wire {}", options_.robot.value,
               participant_->domain_id(), participant_->localhost_only() ? " (localhost only)" : "",
               source_->Describe(), WireName(options_.wire));

  const auto start = std::chrono::steady_clock::now();
  server_watch_.emplace(options_.server_wait, start);
  auto next_map_check = start + options_.map_check_period;
  while (!stop.load()) {
    const auto now = std::chrono::steady_clock::now();
    if (options_.duration.count() > 0 && now - start >= options_.duration) break;
    if (now >= next_map_check) {
      if (auto map = source_->Poll()) {
        if (const Status published = OnNewMap(*map); !published.ok()) {
          spdlog::warn("{}: {}", options_.robot.value, published.message());
        }
      } else if (tile_publisher_ != nullptr && tile_publisher_->pending_tiles() > 0) {
        if (const Status flushed = tile_publisher_->Flush(now); !flushed.ok()) {
          spdlog::warn("{}: {}", options_.robot.value, flushed.message());
        }
        status_.tiles_published = tile_publisher_->tiles_published();
        status_.bytes_published = tile_publisher_->bytes_published();
      }
      if (entity_publisher_ != nullptr) {
        if (const Status published = entity_publisher_->Poll(); !published.ok()) {
          spdlog::warn("{}: {}", options_.robot.value, published.message());
        }
      }
      next_map_check = now + options_.map_check_period;
    }
    RefreshStatus();
    WatchServer(now);
    DrainRobotFrames();
    WatchIdClaims();
    ReportHandshake();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }

  if (baseline_meter_ != nullptr) FinishBaselines();
  spdlog::info("{}: leaving the fleet", options_.robot.value);
  heartbeat_->Stop();
  return status_writer_->Leave(options_.robot);
}

void AgentNode::FinishBaselines() {
  spdlog::info("{}: finishing the byte accounting ({} patches to compress)", options_.robot.value,
               baseline_meter_->totals().patches_pending);
  baseline_meter_->Hurry();
  while (!baseline_meter_->WaitUntilDone(options_.status_period)) RefreshStatus();
  RefreshStatus();
  if (const Status written = heartbeat_->WriteNow(); !written.ok()) {
    spdlog::warn("{}: {}", options_.robot.value, written.message());
  }
  const WireBaselines& b = status_.baselines;
  spdlog::info(
      "{}: the {} map changes published as {} bytes of tiles would have cost {} bytes as whole "
      "grids, {} as patches, {} as zstd -3 patches, {} as zstd -19 patches, {} as LZ4 patches",
      options_.robot.value, b.events, status_.bytes_published, b.grid_bytes, b.patch_bytes,
      b.zstd3_bytes, b.zstd19_bytes, b.lz4_bytes);
  // Leaving disposes the status instance, which can take the place of the final status in a
  // reader that has not taken it yet: give readers one status period to take it.
  std::this_thread::sleep_for(options_.status_period);
}

void AgentOptions::Describe(OptionsPrinter& out) const {
  out.Add("robot", robot);
  out.Add("map_path", map_path);
  out.Add("ros_topic", ros_topic);
  out.Nested("sim", sim);
  out.Add("entities_path", entities_path);
  out.Nested("map_limits", map_limits);
  out.Add("wire", WireName(wire));
  out.Add("measure_baselines", measure_baselines);
  out.Nested("tiles", tiles);
  out.Add("fleet_from_map", fleet_from_map);
  out.Add("unplaced", unplaced);
  out.Add("map_from_robot", map_from_robot);
  out.Add("status_period", status_period);
  out.Add("map_check_period", map_check_period);
  out.Add("duration", duration);
  out.Add("claim_wait", claim_wait);
  out.Add("server_wait", server_wait);
  out.Nested("dds", dds);
}

}  // namespace fleetmap::agent
