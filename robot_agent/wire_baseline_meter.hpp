#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <sys/types.h>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/map_message.hpp"

namespace fleetmap::agent {

// Measures what the map changes an agent publishes as vector tiles would have cost on the
// ROS-native grid wires, at the same changes (issue 17: honest baselines): a whole
// nav_msgs/OccupancyGrid per change (Wire::kGrid), and one map_msgs/OccupancyGridUpdate per changed
// fleet tile, raw (Wire::kGridUpdates), zstd -3 (Wire::kGridUpdatesZstd, the same code), zstd -19
// and LZ4 (CompressedGridUpdate's shape). Each figure is the payload bytes of the sample the real
// type support would write. The first grid, and a grid whose geometry changed, counts as the
// patches of every tile with a known cell: generous to the patch wires, whose real form sends a
// whole grid then (measured on its own by running the agent with that wire).
//
// Compressing at level 19 costs far more than vectorizing, and must not slow the tiles the
// figures are compared with: the patches go to a thread of the lowest priority (SCHED_IDLE),
// which runs when the machine is otherwise idle and may finish after the run; totals() says how
// many patches are still pending. Account() from the agent's thread; totals() and WaitUntilDone()
// from any thread.
class WireBaselineMeter {
 public:
  static StatusOr<std::unique_ptr<WireBaselineMeter>> Create(RobotId robot, Pose2 fleet_from_map,
                                                             double tile_size);
  ~WireBaselineMeter();

  // A new version of the robot's grid, published as tiles: accounts for what changed.
  Status Account(const grid::OccupancyGrid& grid);
  WireBaselines totals() const;
  // True when every patch is accounted for; false if `timeout` passed first.
  bool WaitUntilDone(std::chrono::milliseconds timeout);
  // Back to normal priority: once the run is over, what is left competes fairly for the CPU
  // (at idle priority, other work on the machine could hold it off indefinitely).
  void Hurry();

  // Patches waiting beyond this many cells make Account() wait for the thread, so memory stays
  // bounded however far the accounting falls behind.
  static constexpr size_t kMaxPendingCells = 256u << 20;

 private:
  WireBaselineMeter(RobotId robot, Pose2 fleet_from_map, double tile_size)
      : robot_(std::move(robot)), fleet_from_map_(fleet_from_map), tile_size_(tile_size) {}

  void Run();
  // The payload bytes of `patch` on each patch wire, added to the totals.
  void Measure(const transport::MapUpdate& patch);

  const RobotId robot_;
  const Pose2 fleet_from_map_;
  const double tile_size_;
  std::optional<grid::OccupancyGrid> last_;  // the agent's thread only

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<transport::MapUpdate> pending_;  // guarded by mutex_
  size_t pending_cells_ = 0;                  // guarded by mutex_
  bool measuring_ = false;                    // guarded by mutex_: the thread holds a patch
  bool stop_ = false;                         // guarded by mutex_
  pid_t thread_id_ = 0;                       // guarded by mutex_: the thread's, once it runs
  WireBaselines totals_;                      // guarded by mutex_
  std::thread thread_;                        // last: starts after the rest is made
};

}  // namespace fleetmap::agent
