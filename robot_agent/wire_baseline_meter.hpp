#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

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
// many patches are still pending. That thread may be held off the CPU for seconds at any point,
// so it shares no lock with the agent's thread: batches of patches are handed over through one
// atomic pointer and the totals are atomics. Account() and Hurry() from the agent's thread;
// totals() and WaitUntilDone() from any thread.
class WireBaselineMeter {
 public:
  static StatusOr<std::unique_ptr<WireBaselineMeter>> Create(RobotId robot, Pose2 fleet_from_map,
                                                             double tile_size);
  ~WireBaselineMeter();

  // A new version of the robot's grid, published as tiles: accounts for what changed.
  Status Account(const grid::OccupancyGrid& grid);
  WireBaselines totals() const;
  // True when every patch is accounted for; false if `timeout` passed first.
  bool WaitUntilDone(std::chrono::milliseconds timeout) const;
  // Back to normal priority: once the run is over, what is left competes fairly for the CPU
  // (at idle priority, other work on the machine could hold it off indefinitely).
  void Hurry();

  // Patches waiting beyond this many cells make Account() wait for the thread, so memory stays
  // bounded however far the accounting falls behind.
  static constexpr size_t kMaxPendingCells = 256u << 20;

 private:
  using Batch = std::vector<transport::MapUpdate>;

  WireBaselineMeter(RobotId robot, Pose2 fleet_from_map, double tile_size)
      : robot_(std::move(robot)), fleet_from_map_(fleet_from_map), tile_size_(tile_size) {}

  // Adds `batch` to what the thread has not taken yet.
  void Hand(std::unique_ptr<Batch> batch);
  void Run();
  // The payload bytes of `patch` on each patch wire, added to the totals.
  void Measure(const transport::MapUpdate& patch);

  const RobotId robot_;
  const Pose2 fleet_from_map_;
  const double tile_size_;
  std::optional<grid::OccupancyGrid> last_;  // the agent's thread only

  std::atomic<Batch*> inbox_{nullptr};  // owned: patches the thread has not taken yet
  std::atomic<uint64_t> events_{0};
  std::atomic<uint64_t> grid_bytes_{0};
  std::atomic<uint64_t> patch_bytes_{0};
  std::atomic<uint64_t> zstd3_bytes_{0};
  std::atomic<uint64_t> zstd19_bytes_{0};
  std::atomic<uint64_t> lz4_bytes_{0};
  std::atomic<uint32_t> pending_{0};  // patches handed over and not measured yet
  std::atomic<size_t> pending_cells_{0};
  std::atomic<pid_t> thread_id_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: starts after the rest is made
};

}  // namespace fleetmap::agent
