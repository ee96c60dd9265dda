#pragma once

// A simulated fleet run: a fleetmap-server and N fleetmap-agent processes (built-in robots
// exploring one seeded terrain) over DDS on loopback, watched by an observer in this process that
// reads what any fleet member can read: robot statuses, fused tiles and the fused grid.

#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/fleet/hostile_flood.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {

struct FleetSimOptions {
  int robots = 4;
  sim::TerrainKind kind = sim::TerrainKind::kOffice;
  double size = 40.0;  // metres
  uint32_t seed = 1;
  std::chrono::milliseconds duration{60000};
  double scans_per_second = 25.0;  // each simulated laser
  // What the agents send (fleetmap-agent --wire): tiles, grid, grid-updates, grid-updates-zstd.
  std::string wire = "tiles";
  // With wire "tiles": the agents also measure the grid wires at the same map changes
  // (fleetmap-agent --measure-baselines). The run then waits for their accounting to finish.
  bool measure_baselines = false;
  std::string bin_dir;  // where fleetmap-server and fleetmap-agent are
  // A hostile peer flooding the server while the fleet runs (bench fleet --hostile).
  std::optional<HostileFloodOptions> hostile;

  Status Validate() const;
};

struct FleetRobotResult {
  uint64_t bytes = 0;        // published, as the robot's last status says
  uint64_t updates = 0;      // tiles (or grids and patches) published
  uint64_t whole_grids = 0;  // grids published (the grid wires)
  WireBaselines baselines;   // as the robot's last status says (measure_baselines)
  std::vector<Pose2> path;   // sampled from its statuses
};

struct FleetRunResult {
  std::string wire;
  std::map<std::string, FleetRobotResult> robots;
  uint64_t total_bytes = 0;
  WireBaselines baselines;           // summed over the robots (measure_baselines)
  std::vector<double> latencies_ms;  // fused tile received - the robot update that caused it
                                     // (the honest robots' tiles only)
  grid::OccupancyGrid fused;         // the last fused grid on rt/fleetmap/map
  double server_cpu_seconds = 0.0;
  int64_t server_peak_rss_bytes = 0;
  double seconds = 0.0;  // wall time of the run
  uint64_t hostile_tiles_written = 0;
  std::string server_output;  // what the server printed, its summary table last
  // Robots the server reported lost while every robot ran (none died: each report is false).
  int robots_reported_lost = 0;
};

// Runs the fleet for `options.duration`, then lets the robots leave and stops the server.
// `progress` (optional) is called about once a second with the elapsed seconds, and with -1 once
// a second while the agents finish measuring the grid wires after the run.
StatusOr<FleetRunResult> RunFleet(const FleetSimOptions& options,
                                  const std::function<void(double)>& progress = {});

// The binaries next to this program (build tree or installed): an error names what is missing.
StatusOr<std::string> FindFleetBinaries();

}  // namespace fleetmap::bench
