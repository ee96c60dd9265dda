#pragma once

// A simulated fleet run: a fleetmap-server and N fleetmap-agent processes (built-in robots
// exploring one seeded terrain) over DDS on loopback, watched by an observer in this process that
// reads what any fleet member can read: robot statuses, fused tiles and the fused grid.

#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/fleet/hostile_flood.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {

// Hostile peers in a fleet run: `participants` DDS participants, each a HostileFlood (the flood's
// options, its ids named per participant, its tiles further east), flooding from `start` to
// `stop` after the fleet started (stop 0: until the run ends), so that the run shows honest robots
// before, during and after the flood.
struct HostileAttack {
  HostileFloodOptions flood;
  int participants = 1;
  std::chrono::milliseconds start{0};
  std::chrono::milliseconds stop{0};
};

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
  // Hostile peers flooding the server while the fleet runs (bench fleet --hostile).
  std::optional<HostileAttack> hostile;
  // `fleetmap sim --unknown-poses`: robot i's SLAM map frame is the terrain's frame moved by
  // sim_frames[i] (world_from_map, UnknownPoseFrames); its agent runs --unplaced with --sim-frame
  // and the server has to place it. Empty: every robot maps in the terrain's frame.
  std::vector<Pose2> sim_frames;
  // `fleetmap sim --secure`: a fleet security folder (fleetmap security) holding the identities
  // "server", robot0..robotN-1 and the viewer "observer": every process joins secured. Empty:
  // no DDS Security.
  std::string security_dir;
  // `fleetmap sim --view PORT`: a `fleetmap view` process on the run's domain serves the live page
  // at http://127.0.0.1:PORT/ for as long as the run lasts (-1: none).
  int view_port = -1;
  // `fleetmap sim --params FILE`: a ROS 2 params file with fleetmap_server, fleetmap_agent and
  // fleetmap_view sections, given to each process as --config (docs/configuration.md). What the
  // sim sets on the command line (robot ids, the domain, the terrain) wins over it. Empty: none.
  std::string params_file;
  // `fleetmap sim --shards K` (docs/shards.md): K shard servers, each fusing a strip of the
  // terrain along x, and the aggregator; a reference server fuses every region in the same run
  // (FleetRunResult::reference_fused). 0: one server.
  int shards = 0;

  Status Validate() const;
};

// How the server placed a robot that started at an unknown pose (FleetSimOptions::sim_frames), as
// the observer saw it on rt/fleetmap/robot_frames. Times are seconds since the run started.
struct RobotPlacement {
  Pose2 true_world_from_map;       // the simulator's, hidden from the server
  std::optional<double> joined_s;  // the robot's first status
  // The first time at least kSharedFraction of the robot's known cells lay on the known cells of
  // robots placed at that moment (both read from their tiles, carried into the world frame with
  // the true transforms; checked about once a second). Never set for the anchor.
  std::optional<double> shared_s;
  std::optional<double> placed_s;  // the first state other than unplaced
  // The last robot_frames sample.
  std::string state = "unplaced";
  Pose2 fleet_from_map;
  double confidence = 0.0;
  uint32_t placements = 0;
  std::string placed_against;
  // The robot's map frame: the centroid of its known cells at the end of the run (from its tiles).
  std::optional<Point2> known_centroid;
  int64_t known_cells = 0;       // on the observer's 0.1 m coverage grid, at the end
  double shared_fraction = 0.0;  // the last share checked (before shared_s, or at it)
};

// The share of its known cells a robot must have in common with placed robots to count as having
// "shared enough map" to be placed.
inline constexpr double kSharedFraction = 0.2;

struct FleetRobotResult {
  uint64_t bytes = 0;        // published, as the robot's last status says
  uint64_t updates = 0;      // tiles (or grids and patches) published
  uint64_t whole_grids = 0;  // grids published (the grid wires)
  WireBaselines baselines;   // as the robot's last status says (measure_baselines)
  std::vector<Pose2> path;   // sampled from its statuses; with sim_frames, carried into the
                             // terrain's frame with the true world_from_map
  std::optional<RobotPlacement> placement;  // with sim_frames only
  // Seconds from the agent's start to the observer's first status from it: process start,
  // discovery, the agent's id-claim wait and, when secured, the DDS Security handshakes.
  std::optional<double> joined_s;
  // Secured runs: seconds from the agent's participant's creation until it had authenticated the
  // server (the DDS Security handshake), as the agent logged it.
  std::optional<double> handshake_s;
};

struct FleetRunResult {
  std::string wire;
  std::map<std::string, FleetRobotResult> robots;
  uint64_t total_bytes = 0;
  WireBaselines baselines;           // summed over the robots (measure_baselines)
  std::vector<double> latencies_ms;  // fused tile received - the robot update that caused it
                                     // (the honest robots' tiles only)
  std::vector<double> latency_at_s;  // when each of latencies_ms was received (run seconds)
  grid::OccupancyGrid fused;         // the last fused grid on rt/fleetmap/map (fleet frame)
  // With shards: the regions, and the last grid of the reference server that fused them all in
  // the same run.
  std::vector<ShardRegion> shard_regions;
  grid::OccupancyGrid reference_fused;
  // Takes terrain-frame points into the fleet frame: identity, or with sim_frames the inverse of
  // the anchor's true world_from_map (nullopt while no robot anchored the fleet).
  std::optional<Transform2> fleet_from_world = Transform2::Identity();
  std::string anchor;  // with sim_frames: the robot whose map frame became the fleet frame
  double server_cpu_seconds = 0.0;
  int64_t server_peak_rss_bytes = 0;
  double seconds = 0.0;  // wall time of the run
  uint64_t hostile_tiles_written = 0;
  // With a hostile attack: when its flood started and stopped (run seconds; unset: it did not).
  std::optional<double> flood_started_s;
  std::optional<double> flood_stopped_s;
  // The server's resident memory, sampled about once a second: (run seconds, bytes).
  std::vector<std::pair<double, int64_t>> server_rss;
  std::string server_output;  // what the server printed, its summary table last
  // Robots the server reported lost while every robot ran (none died: each report is false).
  int robots_reported_lost = 0;
  // Bytes sent on the loopback interface during the run: every DDS packet of the fleet, headers
  // and security included, and anything else in the same network namespace (the caller may run
  // the fleet in one of its own), or nullopt where /proc/thread-self/net/dev is not readable.
  std::optional<uint64_t> loopback_bytes;
};

// Runs the fleet for `options.duration`, then lets the robots leave and stops the server.
// `progress` (optional) is called about once a second with the elapsed seconds, and with -1 once
// a second while the agents finish measuring the grid wires after the run.
StatusOr<FleetRunResult> RunFleet(const FleetSimOptions& options,
                                  const std::function<void(double)>& progress = {});

// Seeded random world_from_map transforms for `robots` robots started at unknown poses: any yaw,
// the origin 10 to 50 m from the terrain's in any direction. The same seed gives the same frames.
std::vector<Pose2> UnknownPoseFrames(uint32_t seed, int robots);

// The identity the simulation's observer joins a secured fleet as (a viewer).
inline constexpr char kObserverIdentity[] = "observer";

// Makes the fleet security folder `dir` for a secured simulation (FleetSimOptions::security_dir):
// the fleet CA, the server, robot0..robot<robots-1> and the viewer "observer".
Status MakeSimSecurityFolder(const std::string& dir, int robots);

// The binaries next to this program (build tree or installed): an error names what is missing.
StatusOr<std::string> FindFleetBinaries();

// Total bytes sent on the loopback interface of this thread's network namespace so far, if
// readable.
std::optional<uint64_t> LoopbackBytesSent();

}  // namespace fleetmap::bench
