#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_writer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::agent {

struct TilePublisherOptions {
  double tile_size = 10.0;  // metres
  double epsilon = 0.0;     // metres; <= 0: sqrt(2) * resolution
  // Bandwidth budget for tiles, kilobits per second; 0: none. Over budget, tiles wait (only the
  // newest revision of a waiting tile is sent), and while a backlog of more than 5 s lasts, tiles
  // are re-vectorized with a coarser epsilon (doubling, up to 4x) so fewer bytes carry the map.
  double max_kbps = 0.0;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// Turns successive versions of a robot's grid into vector tiles and publishes only the tiles
// that changed, one keyed instance per (robot, tile), on rt/fleetmap/robot_tiles. A tile is
// re-vectorized when its cells, or the cells just around it that its border vertices depend on,
// change. Call from one thread.
class TilePublisher {
 public:
  static StatusOr<std::unique_ptr<TilePublisher>> Create(transport::Participant& participant,
                                                         RobotId robot, Pose2 fleet_from_map,
                                                         TilePublisherOptions options);

  // A new version of the robot's grid (map frame): queues its changed tiles.
  Status Update(const grid::OccupancyGrid& grid);
  // Publishes what the budget allows now.
  Status Flush(std::chrono::steady_clock::time_point now);

  uint64_t tiles_published() const { return tiles_published_; }
  uint64_t bytes_published() const { return bytes_published_; }
  size_t pending_tiles() const { return pending_.size(); }
  double current_epsilon_factor() const { return epsilon_factor_; }

 private:
  TilePublisher(RobotId robot, Pose2 fleet_from_map, TilePublisherOptions options)
      : robot_(std::move(robot)), fleet_from_map_(fleet_from_map), options_(options) {}

  struct Pending {
    vector_map::VectorMap map;
    bool removed = false;
  };

  RobotId robot_;
  Pose2 fleet_from_map_;
  TilePublisherOptions options_;
  std::unique_ptr<transport::VectorTileWriter> writer_;
  std::map<TileId, uint64_t> tile_hashes_;  // content of each tile and its border context
  std::map<TileId, uint32_t> revisions_;
  std::map<TileId, Pending> pending_;  // waiting for budget
  double tokens_ = 0.0;                // bytes the budget allows now
  std::chrono::steady_clock::time_point last_refill_{};
  double epsilon_factor_ = 1.0;
  uint64_t tiles_published_ = 0;
  uint64_t bytes_published_ = 0;
};

}  // namespace fleetmap::agent
