#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/core/wire.hpp"
#include "common/transport/compressed_map_update_reader.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/map_update_reader.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "server/patched_grid.hpp"

namespace fleetmap::server {

// One robot on a grid wire, as the server reads it: its whole maps on rt/<robot>/map and, on a
// patch wire, the updates on rt/<robot>/map_updates (map_msgs/OccupancyGridUpdate) or
// rt/<robot>/map_updates_zstd (fleetmap_msgs/CompressedGridUpdate), applied to its PatchedGrid.
// Which wire a robot is on, its status says (map_topic). The readers only queue; Poll() does the
// work (inflating included) on the caller's thread, the server's control thread.
class RobotMapFeed {
 public:
  // The grid wire a status's map_topic names for `robot`; nothing for the tile wire.
  static std::optional<Wire> WireOf(const RobotId& robot, const std::string& map_topic);

  static StatusOr<std::unique_ptr<RobotMapFeed>> Create(transport::Participant& participant,
                                                        const RobotId& robot, Wire wire,
                                                        std::shared_ptr<WakeUp> wake_up);
  ~RobotMapFeed();

  struct Received {
    std::optional<transport::MapMessage> grid;  // the robot's grid, when it changed
    std::vector<Status> refused;                // each refused sample, saying why
    uint64_t maps = 0;                          // whole maps taken
    uint64_t updates = 0;                       // updates applied
    uint64_t stale_updates = 0;                 // updates older than the whole map (skipped)
    uint64_t bytes = 0;                         // payload bytes of what was taken
  };
  // Everything received since the last call: whole maps first, then the updates, in order.
  Received Poll();

 private:
  explicit RobotMapFeed(Wire wire) : wire_(wire) {}

  // Counts an update's outcome into `received`.
  template <typename Update>
  void Take(StatusOr<Update>& update, Received* received);

  Wire wire_;
  std::unique_ptr<transport::OccupancyGridReader> map_reader_;
  std::unique_ptr<transport::MapUpdateReader> update_reader_;                 // kGridUpdates
  std::unique_ptr<transport::CompressedMapUpdateReader> zstd_update_reader_;  // kGridUpdatesZstd
  PatchedGrid grid_;
};

}  // namespace fleetmap::server
