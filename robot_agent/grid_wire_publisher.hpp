#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/core/wire.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/compressed_map_update_writer.hpp"
#include "common/transport/map_update_writer.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::agent {

// The grid wires: what a plain ROS 2 robot sends, the baselines the vector tiles are measured
// against. Wire::kGrid publishes the whole nav_msgs/OccupancyGrid on rt/<robot>/map at every
// change. Wire::kGridUpdates publishes the whole grid there once, and again when its geometry
// (size, origin, resolution) changes or when a new reader of the patches joins after changes it
// missed; in between, one map_msgs/OccupancyGridUpdate per changed fleet tile (the tile's cells in
// the robot's grid) on rt/<robot>/map_updates. Wire::kGridUpdatesZstd sends the same patches zstd
// -3 compressed as fleetmap_msgs/CompressedGridUpdate on rt/<robot>/map_updates_zstd. Patches need
// an axis-aligned fleet_from_map (tiles are cut from axis-aligned grids). Call from one thread.
class GridWirePublisher {
 public:
  static StatusOr<std::unique_ptr<GridWirePublisher>> Create(transport::Participant& participant,
                                                             RobotId robot, Pose2 fleet_from_map,
                                                             Wire wire, double tile_size);

  struct Published {
    bool whole_grid = false;
    uint64_t patches = 0;
    uint64_t bytes = 0;
  };
  // A new version of the robot's grid (its map frame).
  StatusOr<Published> Publish(const grid::OccupancyGrid& grid);

  // The topic receivers follow for this robot's map (RobotStatus::map_topic): the grid's, or the
  // patches'.
  const std::string& topic() const { return topic_; }
  uint64_t maps_published() const { return maps_published_; }
  uint64_t patches_published() const { return patches_published_; }
  uint64_t bytes_published() const { return bytes_published_; }

  // A live agent affords zstd level 3 per patch (issue 17).
  static constexpr int kZstdLevel = 3;

 private:
  GridWirePublisher(RobotId robot, Pose2 fleet_from_map, Wire wire, double tile_size)
      : robot_(std::move(robot)),
        fleet_from_map_(fleet_from_map),
        wire_(wire),
        tile_size_(tile_size) {}

  StatusOr<uint64_t> PublishWhole(const grid::OccupancyGrid& grid, Timestamp stamp);
  // Readers of the patches matched since the last call: one may have missed patches.
  bool PatchReaderJoined();

  RobotId robot_;
  Pose2 fleet_from_map_;
  Wire wire_;
  double tile_size_;
  std::string topic_;
  std::unique_ptr<transport::OccupancyGridWriter> grid_writer_;
  std::unique_ptr<transport::MapUpdateWriter> patch_writer_;                 // kGridUpdates
  std::unique_ptr<transport::CompressedMapUpdateWriter> zstd_patch_writer_;  // kGridUpdatesZstd
  std::optional<grid::OccupancyGrid> last_;  // the grid as receivers have it
  bool patched_since_whole_ = false;
  int patch_readers_seen_ = 0;
  uint64_t maps_published_ = 0;
  uint64_t patches_published_ = 0;
  uint64_t bytes_published_ = 0;
};

}  // namespace fleetmap::agent
