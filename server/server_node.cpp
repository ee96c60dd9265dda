#include "server/server_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/transport/topics.hpp"

namespace fleetmap::server {

const char* RobotStateName(RobotRecord::State state) {
  switch (state) {
    case RobotRecord::State::kActive:
      return "active";
    case RobotRecord::State::kLeft:
      return "left";
    case RobotRecord::State::kLost:
      return "lost";
  }
  return "unknown";
}

Status ServerOptions::Validate() const {
  if (duration.count() < 0) return InvalidArgumentError("--duration must be >= 0");
  return Status::Ok();
}

StatusOr<std::unique_ptr<ServerNode>> ServerNode::Create(ServerOptions options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<ServerNode> node(new ServerNode(std::move(options)));
  transport::ParticipantOptions dds = node->options_.dds;
  dds.name = "fleetmap-server";
  FLEETMAP_ASSIGN_OR_RETURN(node->participant_, transport::Participant::Create(dds));
  FLEETMAP_ASSIGN_OR_RETURN(node->status_reader_, transport::RobotStatusReader::Create(
                                                      *node->participant_, node->wake_up_));
  return node;
}

Status ServerNode::Run(const std::atomic<bool>& stop) {
  spdlog::info("server: listening on DDS domain {}{}", participant_->domain_id(),
               participant_->localhost_only() ? " (localhost only)" : "");
  const auto start = std::chrono::steady_clock::now();
  while (!stop.load()) {
    if (options_.duration.count() > 0 &&
        std::chrono::steady_clock::now() - start >= options_.duration) {
      break;
    }
    wake_up_->WaitFor(std::chrono::milliseconds(100));
    HandleRobotEvents();
    HandleMaps();
  }
  PrintSummary();
  // Readers go before the participant that owns their topics.
  for (auto& [robot, record] : robots_) record.map_reader.reset();
  status_reader_.reset();
  return Status::Ok();
}

void ServerNode::HandleRobotEvents() {
  for (const transport::RobotEvent& event : status_reader_->Drain()) {
    switch (event.kind) {
      case transport::RobotEvent::Kind::kStatus:
        OnRobotAlive(event.status);
        break;
      case transport::RobotEvent::Kind::kLeft:
        OnRobotGone(event.robot, RobotRecord::State::kLeft);
        break;
      case transport::RobotEvent::Kind::kLost:
        OnRobotGone(event.robot, RobotRecord::State::kLost);
        break;
      case transport::RobotEvent::Kind::kRejected:
        spdlog::warn("server: dropped a robot status sample: {}", event.error.message());
        break;
    }
  }
}

void ServerNode::OnRobotAlive(const RobotStatus& status) {
  RobotRecord& record = robots_[status.robot];
  const bool joining = record.map_reader == nullptr;
  record.state = RobotRecord::State::kActive;
  record.last_status = status;
  if (!joining) return;

  const std::string topic = transport::RobotMapTopic(status.robot);
  auto reader = transport::OccupancyGridReader::Create(*participant_, topic, wake_up_);
  if (!reader.ok()) {
    spdlog::error("server: robot {} joined but its map cannot be read: {}", status.robot.value,
                  reader.status().message());
    return;
  }
  record.map_reader = std::move(reader).value();
  spdlog::info("server: robot {} joined (map {} x {} at {:.3f} m on {}, fleet_from_map {})",
               status.robot.value, status.map_width, status.map_height, status.map_resolution,
               topic,
               fmt::format("({:.2f}, {:.2f}, {:.3f} rad)", status.fleet_from_map.x,
                           status.fleet_from_map.y, status.fleet_from_map.yaw));
}

void ServerNode::OnRobotGone(const RobotId& robot, RobotRecord::State state) {
  const auto it = robots_.find(robot);
  if (it == robots_.end() || it->second.state != RobotRecord::State::kActive) return;
  RobotRecord& record = it->second;
  HandleMaps();  // keep whatever the robot sent before it went
  record.state = state;
  record.map_reader.reset();
  if (state == RobotRecord::State::kLost) {
    spdlog::warn("server: robot {} lost (no liveliness within {} ms); keeping its last map",
                 robot.value, transport::kRobotLivelinessLease.count());
  } else {
    spdlog::info("server: robot {} left the fleet; keeping its last map", robot.value);
  }
}

void ServerNode::HandleMaps() {
  for (auto& [robot, record] : robots_) {
    if (record.map_reader == nullptr) continue;
    for (StatusOr<transport::MapMessage>& map : record.map_reader->Drain()) {
      if (!map.ok()) {
        ++record.rejected_samples;
        spdlog::warn("server: dropped a map from {}: {}", robot.value, map.status().message());
        continue;
      }
      ++record.maps_received;
      record.bytes_received += map->serialized_bytes;
      spdlog::info("server: map from {}: {} x {} cells at {:.3f} m, {} bytes (total {} bytes)",
                   robot.value, map->grid.width(), map->grid.height(), map->grid.resolution(),
                   map->serialized_bytes, record.bytes_received);
      record.latest_map = std::move(map).value();
    }
  }
}

void ServerNode::PrintSummary() const {
  fmt::print("\n{:<16} {:<8} {:>6} {:>12} {:>12} {:>9}\n", "robot", "state", "maps", "bytes",
             "map cells", "rejected");
  for (const auto& [robot, record] : robots_) {
    const int64_t cells = record.latest_map ? record.latest_map->grid.cell_count() : 0;
    fmt::print("{:<16} {:<8} {:>6} {:>12} {:>12} {:>9}\n", robot.value,
               RobotStateName(record.state), record.maps_received, record.bytes_received, cells,
               record.rejected_samples);
  }
  std::fflush(stdout);
}

}  // namespace fleetmap::server
