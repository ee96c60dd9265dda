#include "common/fusion/map_frame_robots.hpp"

#include <cmath>

namespace fleetmap::fusion {

void MapFrameRobots::PlaceTile(Robot& robot, const TileId& tile, OwnTile& own,
                               std::set<TileId>* changed) {
  own.placed = vector_map::Transformed(own.map, robot.placement->ToTransform(), "fleet");
  own.reaches.clear();
  const auto bounds = vector_map::Bounds(own.placed);
  if (!bounds) return;
  const auto index = [&](double metres) {
    return static_cast<int32_t>(std::floor(metres / tile_size_));
  };
  for (int32_t y = index(bounds->first.y()); y <= index(bounds->second.y()); ++y) {
    for (int32_t x = index(bounds->first.x()); x <= index(bounds->second.x()); ++x) {
      const TileId fleet_tile{x, y};
      own.reaches.insert(fleet_tile);
      robot.own_tiles_by_fleet_tile[fleet_tile].insert(tile);
      changed->insert(fleet_tile);
    }
  }
}

void MapFrameRobots::UnplaceTile(Robot& robot, const TileId& tile, OwnTile& own,
                                 std::set<TileId>* changed) {
  for (const TileId& fleet_tile : own.reaches) {
    const auto it = robot.own_tiles_by_fleet_tile.find(fleet_tile);
    if (it != robot.own_tiles_by_fleet_tile.end()) {
      it->second.erase(tile);
      if (it->second.empty()) robot.own_tiles_by_fleet_tile.erase(it);
    }
    changed->insert(fleet_tile);
  }
  own.reaches.clear();
  own.placed = vector_map::VectorMap();
}

std::set<TileId> MapFrameRobots::UpdateTile(const RobotId& robot_id, const TileId& tile,
                                            vector_map::VectorMap map, Timestamp stamp) {
  Robot& robot = robots_[robot_id];
  ++robot.changes;
  OwnTile& own = robot.tiles[tile];
  std::set<TileId> changed;
  UnplaceTile(robot, tile, own, &changed);
  own.map = std::move(map);
  own.stamp = stamp;
  if (robot.placement) PlaceTile(robot, tile, own, &changed);
  return changed;
}

std::set<TileId> MapFrameRobots::RemoveTile(const RobotId& robot_id, const TileId& tile) {
  std::set<TileId> changed;
  const auto robot = robots_.find(robot_id);
  if (robot == robots_.end()) return changed;
  const auto own = robot->second.tiles.find(tile);
  if (own == robot->second.tiles.end()) return changed;
  ++robot->second.changes;
  UnplaceTile(robot->second, tile, own->second, &changed);
  robot->second.tiles.erase(own);
  return changed;
}

std::set<TileId> MapFrameRobots::Place(const RobotId& robot_id, const Pose2& fleet_from_map) {
  Robot& robot = robots_[robot_id];
  std::set<TileId> changed;
  for (auto& [tile, own] : robot.tiles) UnplaceTile(robot, tile, own, &changed);
  robot.placement = fleet_from_map;
  for (auto& [tile, own] : robot.tiles) PlaceTile(robot, tile, own, &changed);
  return changed;
}

std::set<TileId> MapFrameRobots::Forget(const RobotId& robot_id) {
  std::set<TileId> changed;
  const auto robot = robots_.find(robot_id);
  if (robot == robots_.end()) return changed;
  for (const auto& [fleet_tile, own_tiles] : robot->second.own_tiles_by_fleet_tile) {
    changed.insert(fleet_tile);
  }
  robots_.erase(robot);
  return changed;
}

std::optional<MapFrameRobots::FleetTile> MapFrameRobots::Contribution(const RobotId& robot_id,
                                                                      const TileId& tile) const {
  const auto robot = robots_.find(robot_id);
  if (robot == robots_.end() || !robot->second.placement) return std::nullopt;
  const auto own_tiles = robot->second.own_tiles_by_fleet_tile.find(tile);
  if (own_tiles == robot->second.own_tiles_by_fleet_tile.end()) return std::nullopt;
  FleetTile out;
  out.map.frame_id = "fleet";
  bool first = true;
  for (const TileId& own_tile : own_tiles->second) {
    const OwnTile& own = robot->second.tiles.at(own_tile);
    if (first) {
      out.map.resolution = own.placed.resolution;
      out.map.epsilon = own.placed.epsilon;
      first = false;
    }
    out.map.Append(own.placed);
    out.stamp = std::max(out.stamp, own.stamp);
  }
  if (out.map.obstacles.empty() && out.map.free_space.empty()) return std::nullopt;
  return out;
}

std::optional<Pose2> MapFrameRobots::placement(const RobotId& robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? std::nullopt : it->second.placement;
}

vector_map::VectorMap MapFrameRobots::MapOf(const RobotId& robot_id) const {
  vector_map::VectorMap out;
  const auto robot = robots_.find(robot_id);
  if (robot == robots_.end()) return out;
  bool first = true;
  for (const auto& [tile, own] : robot->second.tiles) {
    if (first) {
      out.resolution = own.map.resolution;
      out.epsilon = own.map.epsilon;
      first = false;
    }
    out.Append(own.map);
  }
  return out;
}

uint64_t MapFrameRobots::changes(const RobotId& robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? 0 : it->second.changes;
}

size_t MapFrameRobots::tile_count(const RobotId& robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? 0 : it->second.tiles.size();
}

std::vector<RobotId> MapFrameRobots::robots() const {
  std::vector<RobotId> out;
  for (const auto& [robot, state] : robots_) out.push_back(robot);
  return out;
}

}  // namespace fleetmap::fusion
