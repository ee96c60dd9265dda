#pragma once

#include <map>
#include <optional>
#include <set>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::fusion {

// The robots whose tiles come in their own map frame (agents started with --unplaced): their
// tiles as received, where the server placed each map frame, and what each contributes to the
// fleet's tiles under that placement.
//
// A robot's contribution to fleet tile F is the geometry of its own tiles that reach F, carried
// into the fleet frame. Vector geometry moves exactly (no resampling), so a placement may turn by
// any angle. A new placement replaces the old one wholesale: the contribution moves, it is never
// counted twice. Not thread-safe: the fusion worker owns it.
class MapFrameRobots {
 public:
  // What a robot gives one fleet tile: its geometry (fleet frame) and the newest stamp in it.
  struct FleetTile {
    vector_map::VectorMap map;
    Timestamp stamp{};
  };

  explicit MapFrameRobots(double tile_size) : tile_size_(tile_size) {}

  // A robot's new revision of one of its tiles (its map frame). Returns the fleet tiles whose
  // contribution changed: none while the robot is not placed.
  std::set<TileId> UpdateTile(const RobotId& robot, const TileId& tile, vector_map::VectorMap map,
                              Timestamp stamp);
  std::set<TileId> RemoveTile(const RobotId& robot, const TileId& tile);
  // Places the robot's map frame at `fleet_from_map` (first placement or revision). Returns the
  // fleet tiles whose contribution changed: those it left and those it covers now.
  std::set<TileId> Place(const RobotId& robot, const Pose2& fleet_from_map);
  // Forgets a robot; returns the fleet tiles it contributed to.
  std::set<TileId> Forget(const RobotId& robot);

  // The robot's contribution to a fleet tile under its placement; nullopt when it has none.
  std::optional<FleetTile> Contribution(const RobotId& robot, const TileId& tile) const;

  bool Knows(const RobotId& robot) const { return robots_.count(robot) > 0; }
  // Where the robot's map frame is placed, if it is.
  std::optional<Pose2> placement(const RobotId& robot) const;
  // The robot's tiles, merged into one map in its own map frame (for registration).
  vector_map::VectorMap MapOf(const RobotId& robot) const;
  // Counts every change of the robot's tiles: tells a registration that the map grew.
  uint64_t changes(const RobotId& robot) const;
  size_t tile_count(const RobotId& robot) const;
  std::vector<RobotId> robots() const;

 private:
  struct OwnTile {
    vector_map::VectorMap map;  // the robot's map frame
    Timestamp stamp{};
    vector_map::VectorMap placed;  // in the fleet frame, while placed
    std::set<TileId> reaches;      // the fleet tiles `placed` reaches
  };
  struct Robot {
    std::map<TileId, OwnTile> tiles;
    std::optional<Pose2> placement;
    std::map<TileId, std::set<TileId>> own_tiles_by_fleet_tile;  // while placed
    uint64_t changes = 0;
  };

  // Carries `own` into the fleet frame under `robot`'s placement and indexes what it reaches;
  // adds those fleet tiles to `changed`.
  void PlaceTile(Robot& robot, const TileId& tile, OwnTile& own, std::set<TileId>* changed);
  // Drops `own`'s fleet-frame copy and index entries; adds what it reached to `changed`.
  void UnplaceTile(Robot& robot, const TileId& tile, OwnTile& own, std::set<TileId>* changed);

  double tile_size_;
  std::map<RobotId, Robot> robots_;
};

}  // namespace fleetmap::fusion
