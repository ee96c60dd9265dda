#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain.hpp"
#include "robot_agent/map_source.hpp"

namespace fleetmap::agent {

struct SimOptions {
  sim::TerrainKind kind = sim::TerrainKind::kOffice;
  double size = 40.0;   // metres
  uint32_t seed = 1;    // the terrain's; every robot of a fleet uses the same
  int robot_index = 0;  // which of the fleet's spread-out start poses is this robot's
  int robots = 1;
  double resolution = 0.05;
  double scans_per_second = 10.0;  // real-time pace of the simulated laser
  int scans_per_map = 5;           // a map snapshot every this many scans
  // Where the robot's SLAM map frame sits in the terrain's (world) frame (--sim-frame): a robot
  // that started at an unknown pose. Its map and pose are handed out in that frame; the server
  // never learns this transform. Identity: the terrain's frame, shared by the fleet.
  Pose2 world_from_map;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// The built-in robot: explores a seeded terrain (common/sim) on its own thread at a real-time
// pace and hands out its SLAM-like map every few scans. The map frame is the terrain's frame,
// shared by every simulated robot (fleet_from_map = identity), unless SimOptions::world_from_map
// moves it: then every map is resampled into the robot's own frame (frame_resample.hpp), about as
// costly as taking the snapshot, and the map's extent holds the whole terrain in every snapshot so
// that the tiles of successive maps line up. Poll() and pose() from the agent's thread.
class SimMapSource : public MapSource {
 public:
  static StatusOr<std::unique_ptr<SimMapSource>> Create(const SimOptions& options);
  ~SimMapSource() override;

  std::optional<grid::OccupancyGrid> Poll() override;
  std::string Describe() const override;
  Pose2 pose() const;
  bool finished() const { return finished_.load(); }

 private:
  explicit SimMapSource(const SimOptions& options) : options_(options) {}
  void Explore(grid::OccupancyGrid truth, Pose2 start);

  SimOptions options_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  mutable std::mutex mutex_;
  std::optional<grid::OccupancyGrid> latest_;  // guarded by mutex_
  Pose2 pose_;                                 // guarded by mutex_
  // Frame rendering cost (world_from_map not identity), for the log line at the end.
  int renders_ = 0;
  double render_seconds_ = 0.0;
};

}  // namespace fleetmap::agent
