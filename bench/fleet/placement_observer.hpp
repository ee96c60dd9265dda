#pragma once

// What `fleetmap sim --unknown-poses` watches beside the fused map: where the server placed each
// robot (rt/fleetmap/robot_frames) and how much map each robot shared with the placed robots when
// it was placed (its tiles on rt/fleetmap/robot_tiles, carried into the terrain's frame with the
// simulator's true transforms, which only this observer knows).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/fleet/fleet_sim.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/core/wake_up.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::bench {

// Owns a robot-frame reader and a robot-tile reader on the observer's participant. One thread
// (RunFleet's) calls everything.
class PlacementObserver {
 public:
  // `sim_frames[i]` is robot "robot<i>"'s true world_from_map; the terrain is [0, size]^2 metres.
  static StatusOr<std::unique_ptr<PlacementObserver>> Create(transport::Participant& participant,
                                                             std::shared_ptr<WakeUp> wake_up,
                                                             std::vector<Pose2> sim_frames,
                                                             double size);
  ~PlacementObserver();

  // Drains both readers into `result` (`now_s`: seconds since the run started); about once a
  // second, re-reads the known cells of robots whose tiles changed and checks how much map the
  // unplaced ones share with the placed ones.
  void Poll(double now_s, FleetRunResult* result);
  // Marks a robot as joined at its first status.
  void Joined(const std::string& robot, double now_s, FleetRunResult* result);
  // The last coverage check and the known cells' centroids into `result`; call it while the
  // robots still run (their tiles go when they leave). Poll() does nothing afterwards.
  void Finish(double now_s, FleetRunResult* result);

 private:
  struct Robot {
    Pose2 world_from_map;
    std::map<TileId, vector_map::VectorMap> tiles;  // its map frame
    bool changed = false;
    std::vector<bool> known;  // on coverage_, terrain frame
    int64_t known_cells = 0;
    Point2 known_sum_world = Point2::Zero();  // sum of the known cells' centres
  };

  PlacementObserver() = default;
  RobotPlacement& PlacementOf(const std::string& robot, FleetRunResult* result);
  void CheckCoverage(double now_s, FleetRunResult* result);

  std::unique_ptr<transport::RobotFrameReader> frames_;
  std::unique_ptr<transport::VectorTileReader> tiles_;
  std::map<std::string, Robot> robots_;
  grid::OccupancyGrid coverage_;  // the terrain at 0.1 m: the geometry of every `known`
  double next_check_s_ = 0.0;
  bool finished_ = false;
};

}  // namespace fleetmap::bench
