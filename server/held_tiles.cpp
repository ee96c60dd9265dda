#include "server/held_tiles.hpp"

#include <fmt/format.h>

#include "common/fusion/tile_cost.hpp"

namespace fleetmap::server {

uint64_t HeldBytes(const transport::TileEvent& event) {
  uint64_t vertices = 0;
  uint64_t rings = 0;
  for (const vector_map::Polyline& polyline : event.tile.map.obstacles) {
    vertices += polyline.points.size();
  }
  for (const vector_map::FreePolygon& polygon : event.tile.map.free_space) {
    rings += 1 + polygon.holes.size();
    vertices += polygon.outer.size();
    for (const auto& hole : polygon.holes) vertices += hole.size();
  }
  return fusion::kBytesPerTile + fusion::kBytesPerVertex * vertices + fusion::kBytesPerRing * rings;
}

std::optional<HeldTiles::Refused> HeldTiles::Hold(transport::TileEvent event,
                                                  const std::string& participant,
                                                  std::chrono::steady_clock::time_point now) {
  const RobotId robot = event.tile.robot_id;
  const TileId tile = event.tile.tile;
  const auto robot_it = robots_.find(robot);
  if (robot_it == robots_.end() && robots_.size() >= limits_.max_robots) {
    return Refused{fusion::Refusal::kUnclaimed,
                   fmt::format("tile ({}, {}) of robot {}, which no status claims: {} unclaimed "
                               "ids already wait for their status",
                               tile.x, tile.y, robot.value, limits_.max_robots)};
  }
  const Held* replaced = nullptr;
  if (robot_it != robots_.end()) {
    const auto tile_it = robot_it->second.find(tile);
    if (tile_it != robot_it->second.end()) replaced = &tile_it->second;
  }
  const size_t robot_tiles = robot_it == robots_.end() ? 0 : robot_it->second.size();
  if (replaced == nullptr && robot_tiles >= limits_.max_tiles_per_robot) {
    // The same quota as a claimed robot's, so the refusal reads the same either way.
    return Refused{
        fusion::Refusal::kTileQuota,
        fmt::format("tile ({}, {}) would be unclaimed robot {}'s tile number {} held; "
                    "a robot may hold {}",
                    tile.x, tile.y, robot.value, robot_tiles + 1, limits_.max_tiles_per_robot)};
  }
  const auto by_participant = tiles_by_participant_.find(participant);
  const size_t participant_tiles =
      by_participant == tiles_by_participant_.end() ? 0 : by_participant->second;
  if (replaced == nullptr && participant_tiles >= limits_.max_tiles_per_participant) {
    return Refused{fusion::Refusal::kTileQuota,
                   fmt::format("tile ({}, {}) of unclaimed robot {}: participant {} already has "
                               "{} tiles waiting for their robots' status",
                               tile.x, tile.y, robot.value, participant, participant_tiles)};
  }
  const uint64_t bytes = HeldBytes(event);
  const uint64_t freed = replaced == nullptr ? 0 : replaced->bytes;
  if (bytes_ - freed + bytes > limits_.max_bytes) {
    return Refused{fusion::Refusal::kMemoryBudget,
                   fmt::format("tile ({}, {}) of unclaimed robot {} would take the tiles waiting "
                               "for a status past {} MB",
                               tile.x, tile.y, robot.value, limits_.max_bytes >> 20)};
  }
  if (replaced != nullptr) Forget(*replaced);
  ++tiles_;
  bytes_ += bytes;
  ++tiles_by_participant_[participant];
  robots_[robot].insert_or_assign(tile, Held{std::move(event), participant, bytes, now});
  return std::nullopt;
}

std::vector<transport::TileEvent> HeldTiles::Release(
    std::chrono::steady_clock::time_point now, const std::function<bool(const RobotId&)>& claimed,
    const std::function<void(const RobotId&, const TileId&)>& expired) {
  std::vector<transport::TileEvent> released;
  for (auto robot = robots_.begin(); robot != robots_.end();) {
    const bool owned = claimed(robot->first);
    for (auto it = robot->second.begin(); it != robot->second.end();) {
      if (!owned && now - it->second.arrived <= limits_.wait) {
        ++it;
        continue;
      }
      Forget(it->second);
      if (owned) {
        released.push_back(std::move(it->second.event));
      } else {
        expired(robot->first, it->first);
      }
      it = robot->second.erase(it);
    }
    robot = robot->second.empty() ? robots_.erase(robot) : std::next(robot);
  }
  return released;
}

void HeldTiles::Forget(const Held& held) {
  --tiles_;
  bytes_ -= held.bytes;
  const auto it = tiles_by_participant_.find(held.participant);
  if (it != tiles_by_participant_.end() && --it->second == 0) tiles_by_participant_.erase(it);
}

}  // namespace fleetmap::server
