#include "bench/fleet/fleet_sim.hpp"

#include <signal.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string_view>
#include <thread>

#include "bench/fleet/bench_flood_command.hpp"
#include "bench/fleet/new_revisions.hpp"
#include "bench/fleet/placement_observer.hpp"
#include "bench/fleet/sim_servers.hpp"
#include "common/process/subprocess.hpp"
#include "common/security/fleet_security.hpp"
#include "common/sim/random.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"

namespace fleetmap::bench {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::steady_clock;

// The handshake time a secured agent logged ("authenticated the server 1.23 s after joining").
std::optional<double> HandshakeSeconds(const std::string& agent_output) {
  constexpr std::string_view kSays = "authenticated the server ";
  const size_t at = agent_output.find(kSays);
  if (at == std::string::npos) return std::nullopt;
  try {
    return std::stod(agent_output.substr(at + kSays.size(), 16));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// `fleetmap view` beside the run (FleetSimOptions::view_port): started once the server listens,
// stopped with SIGTERM when the run ends. A view that cannot start (the port is taken) is
// reported and the run goes on without it: the page is for watching, not for the results.
class SimView {
 public:
  SimView(const FleetSimOptions& options, int domain) {
    if (options.view_port < 0) return;
    std::error_code error;
    const std::string self = fs::read_symlink("/proc/self/exe", error).string();
    std::vector<std::string> argv = {self,
                                     "view",
                                     "--port",
                                     std::to_string(options.view_port),
                                     "--domain",
                                     std::to_string(domain),
                                     "--localhost-only"};
    if (!options.params_file.empty()) argv.insert(argv.end(), {"--config", options.params_file});
    if (!options.security_dir.empty()) {
      argv.insert(argv.end(),
                  {"--security", options.security_dir, "--identity", kObserverIdentity});
    }
    view_ = std::make_unique<process::Subprocess>(std::move(argv));
    if (view_->WaitForOutput("open http://", std::chrono::seconds(20))) {
      std::cerr << fmt::format("\nfleetmap sim: watch the fleet at http://127.0.0.1:{}/\n",
                               options.view_port);
    } else {
      std::cerr << "\nfleetmap sim: the view did not start (the run goes on without it): "
                << view_->Output() << "\n";
      view_.reset();
    }
  }
  // Stops the view and passes on what it says when it stops: browsers served, its traffic.
  ~SimView() {
    if (view_ == nullptr) return;
    view_->Signal(SIGTERM);
    view_->Wait(std::chrono::seconds(10));
    std::istringstream lines(view_->StdOut());
    for (std::string line; std::getline(lines, line);) {
      if (line.find("fleetmap view: open") == std::string::npos) std::cerr << "\n" << line;
    }
    std::cerr << "\n";
  }

 private:
  std::unique_ptr<process::Subprocess> view_;
};

// How long agents that measure the grid wires may take to finish after the run.
constexpr std::chrono::seconds kAccountingWait{900};

// What the observer keeps while the fleet runs. One thread (RunFleet's).
class Observer {
 public:
  static StatusOr<std::unique_ptr<Observer>> Create(int domain, const FleetSimOptions& fleet) {
    std::unique_ptr<Observer> observer(new Observer());
    transport::ParticipantOptions options;
    options.domain_id = domain;
    options.localhost_only = true;
    options.name = "fleetmap-sim-observer";
    if (!fleet.security_dir.empty()) {
      FLEETMAP_RETURN_IF_ERROR(options.UseSecurityFolder(fleet.security_dir, kObserverIdentity));
    }
    FLEETMAP_ASSIGN_OR_RETURN(observer->participant_, transport::Participant::Create(options));
    // The fleet's statuses on a participant of their own, as the server takes them: a flood's
    // thousands of ids must not queue on the socket where the fused tiles arrive, or the observer
    // would time its own backlog (a Nav2 reading the map reads no statuses).
    options.name = "fleetmap-sim-observer-status";
    FLEETMAP_ASSIGN_OR_RETURN(observer->status_participant_,
                              transport::Participant::Create(options));
    FLEETMAP_ASSIGN_OR_RETURN(
        observer->status_,
        transport::RobotStatusReader::Create(*observer->status_participant_, observer->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(
        observer->fused_tiles_,
        transport::VectorTileReader::Create(*observer->participant_, transport::kFusedTilesTopic,
                                            observer->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(
        observer->fused_grid_,
        transport::OccupancyGridReader::Create(*observer->participant_, transport::kFleetMapTopic,
                                               observer->wake_up_));
    if (fleet.shards >= 2) {
      FLEETMAP_ASSIGN_OR_RETURN(observer->reference_grid_,
                                transport::OccupancyGridReader::Create(
                                    *observer->participant_,
                                    transport::ShardMapTopic(kReferenceShard), observer->wake_up_));
    }
    if (!fleet.sim_frames.empty()) {
      FLEETMAP_ASSIGN_OR_RETURN(
          observer->placements_,
          PlacementObserver::Create(*observer->participant_, observer->wake_up_, fleet.sim_frames,
                                    fleet.size));
    }
    return observer;
  }

  ~Observer() {
    placements_.reset();
    status_.reset();
    fused_tiles_.reset();
    fused_grid_.reset();
    reference_grid_.reset();
  }

  // `now_s`: seconds since the run started.
  void Poll(double now_s, FleetRunResult* result) {
    wake_up_->WaitFor(milliseconds(50));
    for (const transport::RobotEvent& event : status_->Drain()) {
      if (event.kind != transport::RobotEvent::Kind::kStatus) continue;
      if (placements_ != nullptr) placements_->Joined(event.robot.value, now_s, result);
      FleetRobotResult& robot = result->robots[event.robot.value];
      if (!robot.joined_s) robot.joined_s = now_s;
      robot.bytes = event.status.bytes_published;
      const bool grid_wire = result->wire != "tiles";
      robot.whole_grids = grid_wire ? event.status.maps_published : 0;
      robot.updates = event.status.tiles_published + robot.whole_grids;
      robot.baselines = event.status.baselines;
      if (robot.path.empty() ||
          (robot.path.back().translation() - event.status.map_from_robot.translation()).norm() >
              0.05) {
        robot.path.push_back(event.status.map_from_robot);
      }
    }
    for (const transport::TileEvent& event : fused_tiles_->Drain()) {
      if (event.kind != transport::TileEvent::Kind::kTile) continue;
      // The first revisions a late reader gets are history, not updates: skip stamps from
      // before the robots started.
      if (event.tile.stamp < started_) continue;
      if (event.tile.tile.x >= hostile_first_tile_x_) continue;  // the hostile peer's
      if (!new_revisions_.Take(event.tile.tile, event.tile.revision)) continue;
      result->latencies_ms.push_back(
          std::chrono::duration<double, std::milli>(event.received - event.tile.stamp).count());
      result->latency_at_s.push_back(now_s);
    }
    for (StatusOr<transport::MapMessage>& map : fused_grid_->Drain()) {
      if (map.ok()) result->fused = std::move(map->grid);
    }
    if (reference_grid_ != nullptr) {
      for (StatusOr<transport::MapMessage>& map : reference_grid_->Drain()) {
        if (map.ok()) result->reference_fused = std::move(map->grid);
      }
    }
    if (placements_ != nullptr) placements_->Poll(now_s, result);
  }

  // The end of the run, while the robots still run.
  void FinishPlacements(double now_s, FleetRunResult* result) {
    if (placements_ != nullptr) placements_->Finish(now_s, result);
  }

  void MarkStart() { started_ = Clock::now(); }
  void IgnoreTilesFrom(int first_tile_x) { hostile_first_tile_x_ = first_tile_x; }

 private:
  Observer() = default;

  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;         // fused tiles and map, placements
  std::unique_ptr<transport::Participant> status_participant_;  // robot statuses
  std::unique_ptr<transport::RobotStatusReader> status_;
  std::unique_ptr<transport::VectorTileReader> fused_tiles_;
  std::unique_ptr<transport::OccupancyGridReader> fused_grid_;
  std::unique_ptr<transport::OccupancyGridReader> reference_grid_;  // --shards
  std::unique_ptr<PlacementObserver> placements_;                   // --unknown-poses
  Timestamp started_;
  int hostile_first_tile_x_ = INT32_MAX;
  NewRevisions new_revisions_;
};

}  // namespace

// Total bytes sent on the loopback interface of this thread's network namespace so far (the
// run's own namespace when the caller entered one), if readable.
std::optional<uint64_t> LoopbackBytesSent() {
  std::ifstream dev("/proc/thread-self/net/dev");
  std::string line;
  while (std::getline(dev, line)) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t name = line.find_first_not_of(' ');
    if (line.compare(name, colon - name, "lo") != 0) continue;
    // Received: bytes packets errs drop fifo frame compressed multicast; then transmitted bytes.
    std::istringstream fields(line.substr(colon + 1));
    uint64_t value = 0;
    for (int i = 0; i < 9; ++i) {
      if (!(fields >> value)) return std::nullopt;
    }
    return value;
  }
  return std::nullopt;
}

Status FleetSimOptions::Validate() const {
  if (robots < 1 || robots > 64) return InvalidArgumentError("--robots must be in 1..64");
  if (duration.count() <= 0) return InvalidArgumentError("--duration must be > 0 seconds");
  if (!(scans_per_second > 0.0)) return InvalidArgumentError("--rate must be > 0 scans/s");
  if (!params_file.empty() && !std::ifstream(params_file)) {
    return InvalidArgumentError("--params " + params_file + ": cannot be read");
  }
  if (shards != 0 && (shards < 2 || shards > 8)) {
    return InvalidArgumentError("--shards must be in 2..8");
  }
  if (shards >= 2 && !sim_frames.empty()) {
    return InvalidArgumentError(
        "--shards needs known poses: a shard never takes a robot's frame as the fleet frame "
        "(docs/shards.md)");
  }
  if (shards >= 2 && wire != "tiles") {
    return InvalidArgumentError("--shards runs the tile wire only");
  }
  if (hostile) {
    if (hostile->participants < 1 || hostile->participants > 16) {
      return InvalidArgumentError("--hostile-participants must be in 1..16");
    }
    if (hostile->flood.ids < 1 || hostile->flood.ids > 10000) {
      return InvalidArgumentError("--hostile-ids must be in 1..10000");
    }
    if (hostile->stop.count() > 0 && hostile->stop <= hostile->start) {
      return InvalidArgumentError("the hostile flood must stop after it starts");
    }
  }
  if (wire != "tiles" && wire != "grid" && wire != "grid-updates" && wire != "grid-updates-zstd") {
    return InvalidArgumentError(
        std::string("the wire must be tiles, grid, grid-updates or grid-updates-zstd, not \"")
            .append(wire)
            .append("\""));
  }
  if (measure_baselines && wire != "tiles") {
    return InvalidArgumentError("the grid wires are measured beside the tile wire only");
  }
  if (!sim_frames.empty() && static_cast<int>(sim_frames.size()) != robots) {
    return InvalidArgumentError("one sim frame per robot");
  }
  if (!sim_frames.empty() && (measure_baselines || wire != "tiles")) {
    return InvalidArgumentError("robots at unknown poses run on the tile wire, unmeasured");
  }
  if (view_port < -1 || view_port > 65535) return InvalidArgumentError("--view must be a TCP port");
  if (size < sim::kMinTerrainSize || size > sim::kMaxTerrainSize) {
    return InvalidArgumentError("--size must be in " + std::to_string(sim::kMinTerrainSize) + ".." +
                                std::to_string(sim::kMaxTerrainSize) + " metres");
  }
  return Status::Ok();
}

std::vector<Pose2> UnknownPoseFrames(uint32_t seed, int robots) {
  sim::Random random(seed * 7919u + 17u);
  std::vector<Pose2> frames;
  for (int i = 0; i < robots; ++i) {
    const double direction = random.Uniform(-M_PI, M_PI);
    const double distance = random.Uniform(10.0, 50.0);
    frames.push_back({distance * std::cos(direction), distance * std::sin(direction),
                      random.Uniform(-M_PI, M_PI)});
  }
  return frames;
}

Status MakeSimSecurityFolder(const std::string& dir, int robots) {
  FLEETMAP_RETURN_IF_ERROR(security::InitFleet(dir, security::FleetSecurityOptions{}));
  const security::Validity validity = security::Validity::FromNow(1);
  for (int i = 0; i < robots; ++i) {
    FLEETMAP_RETURN_IF_ERROR(
        security::Enroll(dir, "robot" + std::to_string(i), security::Role::kRobot, validity));
  }
  return security::Enroll(dir, kObserverIdentity, security::Role::kViewer, validity);
}

StatusOr<std::string> FindFleetBinaries() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) return NotFoundError("cannot locate this program: " + error.message());
  const fs::path dir = self.parent_path();
  // Installed side by side, or the build tree (cli/, server/, robot_agent/).
  for (const fs::path& candidate : {dir, dir.parent_path()}) {
    if (fs::exists(candidate / "fleetmap-server") && fs::exists(candidate / "fleetmap-agent")) {
      return candidate.string() + "/";
    }
    if (fs::exists(candidate / "server/fleetmap-server") &&
        fs::exists(candidate / "robot_agent/fleetmap-agent")) {
      return candidate.string() + "/";
    }
  }
  return NotFoundError("fleetmap-server and fleetmap-agent are not next to " + self.string());
}

StatusOr<FleetRunResult> RunFleet(const FleetSimOptions& options,
                                  const std::function<void(double)>& progress) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  const auto binary = [&](const std::string& name, const std::string& subdir) {
    const std::string side_by_side = options.bin_dir + name;
    return fs::exists(side_by_side) ? side_by_side : options.bin_dir + subdir + "/" + name;
  };
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  FleetRunResult result;
  result.wire = options.wire;
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<Observer> observer, Observer::Create(domain, options));

  std::vector<std::string> security_args;
  if (!options.security_dir.empty()) security_args = {"--security", options.security_dir};
  std::vector<std::string> server_argv = {binary("fleetmap-server", "server"), "--map-period",
                                          "0.5"};
  server_argv.insert(server_argv.end(), security_args.begin(), security_args.end());
  std::vector<std::string> config_args;
  if (!options.params_file.empty()) config_args = {"--config", options.params_file};
  server_argv.insert(server_argv.end(), config_args.begin(), config_args.end());
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<SimServers> servers,
                            SimServers::Start(server_argv, env, options.size, options.shards));
  result.shard_regions = servers->regions();
  const SimView view(options, domain);
  observer->MarkStart();
  const auto start = steady_clock::now();
  const std::optional<uint64_t> loopback_at_start = LoopbackBytesSent();
  std::vector<std::unique_ptr<process::Subprocess>> agents;
  for (int i = 0; i < options.robots; ++i) {
    std::vector<std::string> argv = {binary("fleetmap-agent", "robot_agent"),
                                     "--robot-id",
                                     "robot" + std::to_string(i),
                                     "--sim",
                                     std::string(sim::TerrainKindName(options.kind)),
                                     "--sim-size",
                                     std::to_string(options.size),
                                     "--sim-seed",
                                     std::to_string(options.seed),
                                     "--sim-robot-index",
                                     std::to_string(i),
                                     "--sim-robots",
                                     std::to_string(options.robots),
                                     "--sim-rate",
                                     std::to_string(options.scans_per_second),
                                     "--wire",
                                     options.wire};
    if (options.measure_baselines) argv.push_back("--measure-baselines");
    argv.insert(argv.end(), security_args.begin(), security_args.end());
    argv.insert(argv.end(), config_args.begin(), config_args.end());
    if (!options.sim_frames.empty()) {
      const Pose2& frame = options.sim_frames[i];
      argv.insert(argv.end(), {"--unplaced", "--sim-frame", fmt::format("{:.6f}", frame.x),
                               fmt::format("{:.6f}", frame.y), fmt::format("{:.9f}", frame.yaw)});
    }
    agents.push_back(std::make_unique<process::Subprocess>(std::move(argv), env));
  }

  // The flood is a process of its own (`fleetmap bench flood`): what building and sending its
  // tiles costs is not charged to this process, whose observer measures the honest latencies. It
  // runs at a lower priority (nice 10) because a real attacker brings its own CPU: on a small
  // machine at full priority it takes the cores the server and the honest agents need, and the
  // bench would measure the machine, not the server's defences.
  std::vector<std::string> flood_argv;
  if (options.hostile) {
    const HostileFloodOptions& flood = options.hostile->flood;
    observer->IgnoreTilesFrom(flood.first_tile_x);
    flood_argv = {"/usr/bin/nice",
                  "-n",
                  "10",
                  binary("fleetmap", "cli"),
                  "bench",
                  "flood",
                  "--participants",
                  std::to_string(options.hostile->participants),
                  "--ids",
                  std::to_string(flood.ids),
                  "--robot",
                  flood.robot,
                  "--heavy-tiles",
                  std::to_string(flood.heavy_tiles),
                  "--rate",
                  fmt::format("{}", flood.rate_hz),
                  "--keys",
                  std::to_string(flood.distinct_keys),
                  "--first-tile-x",
                  std::to_string(flood.first_tile_x)};
  }
  std::unique_ptr<process::Subprocess> flood;
  const auto seconds_since_start = [&] {
    return std::chrono::duration<double>(steady_clock::now() - start).count();
  };
  const auto start_flood = [&]() -> Status {
    flood = std::make_unique<process::Subprocess>(flood_argv, env);
    if (!flood->started()) return UnavailableError("could not start " + flood_argv[3]);
    result.flood_started_s = seconds_since_start();
    return Status::Ok();
  };
  const auto stop_flood = [&] {
    flood->Signal(SIGINT);
    if (!flood->Wait(std::chrono::seconds(30))) {
      flood->Signal(SIGKILL);
      (void)flood->Wait(std::chrono::seconds(5));
    }
    result.hostile_tiles_written += TilesWrittenByFlood(flood->StdOut());
    result.flood_stopped_s = seconds_since_start();
    flood.reset();
  };
  auto next_progress = start;
  auto next_rss = start;
  while (steady_clock::now() - start < options.duration) {
    const auto now = steady_clock::now();
    if (options.hostile && !result.flood_started_s && now - start >= options.hostile->start) {
      FLEETMAP_RETURN_IF_ERROR(start_flood());
    }
    if (flood && options.hostile->stop.count() > 0 && now - start >= options.hostile->stop) {
      stop_flood();
    }
    observer->Poll(seconds_since_start(), &result);
    if (now >= next_rss) {
      if (const int64_t rss = servers->RssBytes(); rss > 0) {
        result.server_rss.emplace_back(seconds_since_start(), rss);
      }
      next_rss += std::chrono::seconds(1);
    }
    if (progress && now >= next_progress) {
      progress(std::chrono::duration<double>(now - start).count());
      next_progress += std::chrono::seconds(1);
    }
  }
  observer->FinishPlacements(seconds_since_start(), &result);
  if (const std::optional<uint64_t> now = LoopbackBytesSent(); now && loopback_at_start) {
    result.loopback_bytes = *now - *loopback_at_start;
  }
  // The server's resources while it still runs, then an orderly end: robots leave first.
  const std::string during_run = servers->Output();
  for (size_t at = during_run.find(" lost (no liveliness"); at != std::string::npos;
       at = during_run.find(" lost (no liveliness", at + 1)) {
    ++result.robots_reported_lost;
  }
  result.server_cpu_seconds = servers->CpuSeconds();
  result.server_peak_rss_bytes = servers->PeakRssBytes();
  if (flood) stop_flood();
  for (auto& agent : agents) agent->Signal(SIGTERM);
  // Agents that measure the grid wires finish compressing first, still reporting (their
  // accounting ran at idle priority and may lag far behind a busy run).
  const auto agents_deadline =
      steady_clock::now() +
      (options.measure_baselines ? kAccountingWait : std::chrono::seconds(10));
  const auto all_exited = [&] {
    return std::all_of(agents.begin(), agents.end(),
                       [](auto& agent) { return agent->Wait(milliseconds(0)).has_value(); });
  };
  auto next_note = steady_clock::now();
  while (!all_exited() && steady_clock::now() < agents_deadline) {
    observer->Poll(seconds_since_start(), &result);
    if (progress && options.measure_baselines && steady_clock::now() >= next_note) {
      progress(-1.0);
      next_note += std::chrono::seconds(1);
    }
  }
  for (int i = 0; i < options.robots; ++i) {
    if (const std::optional<double> handshake = HandshakeSeconds(agents[i]->Output())) {
      result.robots["robot" + std::to_string(i)].handshake_s = handshake;
    }
  }
  const auto drain_until = steady_clock::now() + std::chrono::milliseconds(1500);
  while (steady_clock::now() < drain_until) observer->Poll(seconds_since_start(), &result);
  servers->Stop();
  result.server_output = servers->Output();
  result.seconds = std::chrono::duration<double>(steady_clock::now() - start).count();
  if (!options.sim_frames.empty()) {
    // The fused map is in the anchor's frame and each path in its robot's: the truth carries
    // them into the terrain's frame, where the report scores and draws them.
    result.fleet_from_world.reset();
    for (auto& [name, robot] : result.robots) {
      if (!robot.placement) continue;
      const Transform2 world_from_map = robot.placement->true_world_from_map.ToTransform();
      if (name == result.anchor) result.fleet_from_world = world_from_map.inverse();
      for (Pose2& pose : robot.path) {
        pose = Pose2::FromTransform(world_from_map * pose.ToTransform());
      }
    }
  }
  for (const auto& [name, robot] : result.robots) {
    result.total_bytes += robot.bytes;
    WireBaselines& sum = result.baselines;
    sum.events += robot.baselines.events;
    sum.grid_bytes += robot.baselines.grid_bytes;
    sum.patch_bytes += robot.baselines.patch_bytes;
    sum.zstd3_bytes += robot.baselines.zstd3_bytes;
    sum.zstd19_bytes += robot.baselines.zstd19_bytes;
    sum.lz4_bytes += robot.baselines.lz4_bytes;
    sum.patches_pending += robot.baselines.patches_pending;
  }
  return result;
}

}  // namespace fleetmap::bench
