#pragma once

// A differential-drive robot (Pioneer 3-DX-like: 0.19 m half-width, turns in place) with a 2D laser
// that explores a terrain on its own and maps it: it scans, integrates the scan into its map with
// the pose its SLAM believes (SlamErrorModel), plans to the nearest frontier of its own map
// (FrontierPlanner), turns towards the next leg, drives it (scanning every scan_distance metres
// and every scan_rotation radians of turn), replans every replan_distance metres, and turns a full
// circle at each goal. The controller drives on the true pose (a real robot localises on its own
// map, which is consistent with itself); only the map carries the SLAM error. The run ends when no
// reachable frontier is left or a budget (scans, distance) is spent.
//
// Deterministic: the same truth, start and options (seed included) give the same map bytes.
//
// Thread-safety: an ExplorationSimulator is immutable; Run() may be called concurrently.

#include <cstdint>
#include <functional>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/frontier_planner.hpp"
#include "common/sim/laser_scanner.hpp"
#include "common/sim/occupancy_mapper.hpp"
#include "common/sim/slam_error_model.hpp"

namespace fleetmap::sim {

struct ExplorationOptions {
  LaserOptions laser;
  MapperOptions mapper;  // block_size is set from planner_block (below)
  SlamErrorOptions error;
  FrontierOptions frontier;
  uint32_t seed = 0;
  double robot_radius = 0.19;  // metres, > 0, < frontier.inflation_radius
  double planner_block = 0.2;  // metres, side of a planner block (rounded to whole cells)
  double step = 0.1;           // metres per motion step (collision checks), > 0
  double scan_distance = 0.5;  // metres driven between scans, > 0
  double scan_rotation = 0.7853981633974483;  // radians turned between scans, > 0
  double replan_distance = 4.0;               // metres driven before replanning, > 0
  bool spin_at_goal = true;       // a full turn at each goal (the laser sees 180 degrees)
  int max_scans = 60000;          // budget, >= 1
  double max_distance = 50000.0;  // metres, budget, > 0
};

struct ExplorationProgress {
  int scans = 0;
  double distance = 0.0;
  int goals = 0;
};

struct ExplorationResult {
  grid::OccupancyGrid map;        // the robot's trinary map, the truth's geometry
  std::vector<Pose2> trajectory;  // true pose of every scan
  std::vector<Pose2> beliefs;     // believed pose of every scan
  int scans = 0;
  double distance = 0.0;  // metres driven
  int goals_reached = 0;
  int goals_failed = 0;   // blocked by an obstacle the map did not show
  bool explored = false;  // false when a budget ended the run
};

// After every scan of a live run: how many scans so far, the robot's true pose, and its map as it
// stands (call ToGrid() for a snapshot). Return false to end the run early (explored = false).
using ScanObserver =
    std::function<bool(int scans, const Pose2& pose, const OccupancyMapper& mapper)>;

class ExplorationSimulator {
 public:
  // Errors (kInvalidArgument) name the option (laser, mapper, error model, frontier, budgets).
  static StatusOr<ExplorationSimulator> Create(const ExplorationOptions& options);

  const ExplorationOptions& options() const { return options_; }

  // Explores `truth` from `start`. Errors (kInvalidArgument): start outside the grid or not free,
  // truth with a rotated origin. `on_progress` (optional) is called after every 100th scan.
  // `on_scan` (optional) is called after every scan, e.g. to publish the map live.
  StatusOr<ExplorationResult> Run(
      const grid::OccupancyGrid& truth, const Pose2& start,
      const std::function<void(const ExplorationProgress&)>& on_progress = {},
      const ScanObserver& on_scan = {}) const;

 private:
  ExplorationSimulator(const ExplorationOptions& options, LaserScanner laser)
      : options_(options), laser_(std::move(laser)) {}

  ExplorationOptions options_;
  LaserScanner laser_;
};

}  // namespace fleetmap::sim
