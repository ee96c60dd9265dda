#include "robot_agent/agent_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::agent {
namespace {

bool Finite(const Pose2& pose) {
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.yaw);
}

}  // namespace

Status AgentOptions::Validate() const {
  if (!IsValidRobotName(robot.value)) {
    return InvalidArgumentError("--robot-id \"" + robot.value +
                                "\" is not a valid robot name ([A-Za-z][A-Za-z0-9_]*, <= 64)");
  }
  if (map_path.empty()) return InvalidArgumentError("--map is required");
  if (!Finite(fleet_from_map)) return InvalidArgumentError("--fleet-from-map is not finite");
  if (!Finite(map_from_robot)) return InvalidArgumentError("--pose is not finite");
  if (status_period.count() <= 0) return InvalidArgumentError("the status period must be > 0");
  if (map_check_period.count() <= 0)
    return InvalidArgumentError("the map check period must be > 0");
  if (duration.count() < 0) return InvalidArgumentError("--duration must be >= 0");
  return Status::Ok();
}

StatusOr<std::unique_ptr<AgentNode>> AgentNode::Create(AgentOptions options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<AgentNode> node(new AgentNode(std::move(options)));
  FLEETMAP_RETURN_IF_ERROR(node->LoadMap());

  transport::ParticipantOptions dds = node->options_.dds;
  dds.name = "fleetmap-agent/" + node->options_.robot.value;
  FLEETMAP_ASSIGN_OR_RETURN(node->participant_, transport::Participant::Create(dds));
  FLEETMAP_ASSIGN_OR_RETURN(node->status_writer_,
                            transport::RobotStatusWriter::Create(*node->participant_));
  FLEETMAP_ASSIGN_OR_RETURN(
      node->map_writer_, transport::OccupancyGridWriter::Create(
                             *node->participant_, transport::RobotMapTopic(node->options_.robot)));

  RobotStatus& status = node->status_;
  status.robot = node->options_.robot;
  status.fleet_from_map = node->options_.fleet_from_map;
  status.map_from_robot = node->options_.map_from_robot;
  status.map_topic = transport::RobotMapTopic(node->options_.robot);
  return node;
}

Status AgentNode::LoadMap() {
  FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap loaded, grid::LoadMap(options_.map_path));
  std::error_code error;
  map_mtime_ = std::filesystem::last_write_time(options_.map_path, error);
  map_ = std::move(loaded.grid);
  return Status::Ok();
}

Status AgentNode::PublishMap() {
  transport::MapMessage message;
  message.grid = map_;
  message.frame_id = options_.robot.value + "/map";
  message.stamp = Clock::now();
  FLEETMAP_ASSIGN_OR_RETURN(const size_t bytes, map_writer_->Write(message));
  ++status_.map_revision;
  ++status_.maps_published;
  status_.bytes_published += bytes;
  status_.map_width = static_cast<uint32_t>(map_.width());
  status_.map_height = static_cast<uint32_t>(map_.height());
  status_.map_resolution = map_.resolution();
  spdlog::info("{}: published map revision {} ({} x {} cells, {} bytes) on {}",
               options_.robot.value, status_.map_revision, map_.width(), map_.height(), bytes,
               status_.map_topic);
  return Status::Ok();
}

Status AgentNode::PublishStatus() {
  status_.stamp = Clock::now();
  ++status_.sequence_number;
  return status_writer_->Write(status_);
}

void AgentNode::ReloadMapIfChanged() {
  std::error_code error;
  const auto mtime = std::filesystem::last_write_time(options_.map_path, error);
  if (error || mtime == map_mtime_) return;
  if (const Status loaded = LoadMap(); !loaded.ok()) {
    map_mtime_ = mtime;  // report a broken file once, not every period
    spdlog::warn("{}: keeping the previous map: {}", options_.robot.value, loaded.message());
    return;
  }
  if (const Status published = PublishMap(); !published.ok()) {
    spdlog::warn("{}: {}", options_.robot.value, published.message());
  }
}

Status AgentNode::Run(const std::atomic<bool>& stop) {
  FLEETMAP_RETURN_IF_ERROR(PublishMap());
  FLEETMAP_RETURN_IF_ERROR(PublishStatus());
  spdlog::info("{}: in the fleet on DDS domain {}{}", options_.robot.value,
               participant_->domain_id(),
               participant_->localhost_only() ? " (localhost only)" : "");

  const auto start = std::chrono::steady_clock::now();
  auto next_status = start + options_.status_period;
  auto next_map_check = start + options_.map_check_period;
  while (!stop.load()) {
    const auto now = std::chrono::steady_clock::now();
    if (options_.duration.count() > 0 && now - start >= options_.duration) break;
    if (now >= next_status) {
      if (const Status written = PublishStatus(); !written.ok()) {
        spdlog::warn("{}: {}", options_.robot.value, written.message());
      }
      next_status += options_.status_period;
    }
    if (now >= next_map_check) {
      ReloadMapIfChanged();
      next_map_check += options_.map_check_period;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }

  spdlog::info("{}: leaving the fleet", options_.robot.value);
  return status_writer_->Leave(options_.robot);
}

}  // namespace fleetmap::agent
