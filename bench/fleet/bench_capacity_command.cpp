#include "bench/fleet/bench_capacity_command.hpp"

#include <fmt/format.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/new_revisions.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/wake_up.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/transport/vector_tile_writer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::bench {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;

constexpr double kTileSize = 10.0;         // the server's default fleet tiling
constexpr int kRobotsPerBuilding = 8;      // robots sharing one building, each at its own phase
constexpr int kRobotsPerParticipant = 16;  // the server's --max-robots-per-participant default
constexpr double kP99TargetMs = 50.0;

struct CapacityArgs {
  std::vector<int> robots = {8, 16, 32, 64, 128, 256};
  double stage_s = 20.0;  // measured seconds per fleet size, once every robot was fused
  // Seconds between the join and the measurement: what discovery delayed (a writer matched late
  // hands over its history at once, old stamps and all) is the join's, not fusion's.
  double settle_s = 5.0;
  double rate = 1.0;     // updates per second per robot
  std::string map_path;  // a real SLAM map; empty: a simulated office
  double size = 40.0;    // the simulated office's side, metres
  int steps = 24;        // reveal steps of a building
  int server_core = 1;   // the server's core (taskset); -1: not pinned
  // "simple" (the default discovery), "server" (a Fast DDS discovery server), or "both".
  std::string discovery = "simple";
  // Shard servers per stage (docs/shards.md), each fusing a strip of the buildings' columns,
  // shard i pinned to core (server_core + i) mod cores; 1: one server.
  std::vector<int> shards = {1};
  // Robots per load-generator participant (an agent process holds one robot: 1). Fewer robots
  // per participant, more participants: how discovery grows is measured with 1.
  int robots_per_participant = kRobotsPerParticipant;
  std::string out_dir = "out/bench-capacity";
};

constexpr int kBuildingsPerRow = 8;
// The column a building takes in its row: consecutive buildings alternate between the halves
// (and quarters) of the row, so that a fleet of a few buildings spreads over every shard's strip.
constexpr int kColumnOfBuilding[kBuildingsPerRow] = {0, 4, 2, 6, 1, 5, 3, 7};

// One building's exploration, recorded: at each step, the tiles that changed since the previous
// step (fleet frame, the building at the origin).
struct TileStream {
  std::vector<std::map<TileId, vector_map::VectorMap>> steps;
  int tiles_wide = 1;  // the building's extent in tiles
  int tiles_high = 1;
};

// The building revealed column by column: step k knows the cells left of (k + 1) / steps of its
// width. Vectorized once per step; each step keeps the tiles whose geometry changed.
StatusOr<TileStream> RecordStream(const grid::OccupancyGrid& building, int steps) {
  TileStream stream;
  vector_map::TiledVectorizeOptions options;
  options.tile_size = kTileSize;
  std::map<TileId, vector_map::VectorMap> previous;
  for (int step = 0; step < steps; ++step) {
    grid::OccupancyGrid known = building;
    const int known_columns = building.width() * (step + 1) / steps;
    for (int y = 0; y < known.height(); ++y) {
      for (int x = known_columns; x < known.width(); ++x) known.at(x, y) = grid::kUnknownValue;
    }
    FLEETMAP_ASSIGN_OR_RETURN(vector_map::TiledVectorMap tiled,
                              vector_map::VectorizeTiled(known, Transform2::Identity(), options));
    std::map<TileId, vector_map::VectorMap> changed;
    for (auto& [tile, map] : tiled.tiles) {
      const auto before = previous.find(tile);
      const bool same = before != previous.end() &&
                        before->second.ObstacleVertexCount() == map.ObstacleVertexCount() &&
                        before->second.FreeVertexCount() == map.FreeVertexCount();
      if (!same) changed[tile] = map;
      stream.tiles_wide = std::max(stream.tiles_wide, tile.x + 1);
      stream.tiles_high = std::max(stream.tiles_high, tile.y + 1);
    }
    previous = std::move(tiled.tiles);
    stream.steps.push_back(std::move(changed));
  }
  return stream;
}

StatusOr<grid::OccupancyGrid> Building(const CapacityArgs& args) {
  if (!args.map_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap loaded, grid::LoadMap(args.map_path));
    // At the origin, so that the building's tiles start at tile (0, 0).
    const grid::OccupancyGrid& map = loaded.grid;
    grid::OccupancyGrid grid(map.width(), map.height(), map.resolution(), Pose2{0.0, 0.0, 0.0});
    grid.mutable_data() = map.data();
    return grid;
  }
  sim::TerrainOptions options;
  options.kind = sim::TerrainKind::kOffice;
  options.size = args.size;
  options.seed = 1;
  FLEETMAP_ASSIGN_OR_RETURN(sim::TerrainGenerator generator,
                            sim::TerrainGenerator::Create(options));
  return sim::RasterizeTerrain(generator.Generate(), 0.05);
}

// `map` moved by whole tiles: every vertex moves by a multiple of the lattice's quantum, so it
// stays on the lattice the codec sends it on.
vector_map::VectorMap ShiftedByTiles(vector_map::VectorMap map, int dx, int dy) {
  const Vector2 offset(dx * kTileSize, dy * kTileSize);
  for (vector_map::Polyline& line : map.obstacles) {
    for (Point2& point : line.points) point += offset;
  }
  for (vector_map::FreePolygon& polygon : map.free_space) {
    for (Point2& point : polygon.outer) point += offset;
    for (auto& hole : polygon.holes) {
      for (Point2& point : hole) point += offset;
    }
  }
  return map;
}

size_t CountOf(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

double Percentile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t index =
      std::min(values.size() - 1, static_cast<size_t>(std::ceil(share * values.size())) - 1);
  return values[index];
}

// The server's CPU time (user + system), from /proc.
std::optional<double> CpuSeconds(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return std::nullopt;
  // Fields after the command name (in parentheses, which may hold spaces): state is field 3,
  // utime 14, stime 15.
  std::istringstream fields(line.substr(line.rfind(')') + 2));
  std::string field;
  double ticks = 0.0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14 || i == 15) ticks += std::stod(field);
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// A line of /proc/<pid>/status in MB (VmRSS, VmHWM).
std::optional<double> StatusMb(pid_t pid, const std::string& key) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) / 1024.0;
  }
  return std::nullopt;
}

struct StageOutcome {
  int robots = 0;
  int participants = 0;           // the load generator's (the server's and the reader's aside)
  std::string discovery;          // "simple" or "server"
  std::optional<double> join_mb;  // loopback bytes until every robot joined (with first tiles)
  // CPU seconds from the stage's start to the join: the discovery server's process (with
  // --discovery server), and the load generator's participants (this process).
  std::optional<double> discovery_server_cpu_s;
  std::optional<double> participants_cpu_s;
  double offered_per_s = 0.0;  // robot tile updates sent per second
  double fused_per_s = 0.0;    // fused tile updates received per second
  double p50_ms = 0.0;
  double p99_ms = 0.0;
  size_t latencies = 0;
  std::optional<double> joined_s;  // until the server followed every robot, and fused each building
  double server_cores = 0.0;       // CPU seconds per second over the measured window
  int shards = 1;
  std::vector<double> shard_cores;  // each shard server's share of server_cores
  double server_rss_mb = 0.0;
  double server_peak_mb = 0.0;
};

// N robots of the load generator: one participant, status writer and tile writer per
// `robots_per_participant` robots (16 by default), dealt round so that the eight robots of a
// building are eight participants' (eight agents that confirm each other's walls, as on a real
// floor).
class LoadGenerator {
 public:
  static StatusOr<std::unique_ptr<LoadGenerator>> Create(int domain, int robots,
                                                         int robots_per_participant,
                                                         const TileStream& stream, double rate,
                                                         const std::string& discovery_server) {
    std::unique_ptr<LoadGenerator> self(new LoadGenerator(stream, rate));
    // At most robots_per_participant each, and at least as many participants as robots share a
    // building.
    const int participants =
        std::max((robots + robots_per_participant - 1) / robots_per_participant,
                 std::min(robots, kRobotsPerBuilding));
    for (int index = 0; index < participants; ++index) {
      transport::ParticipantOptions options;
      options.domain_id = domain;
      options.localhost_only = true;
      options.intraprocess_delivery = false;
      options.name = fmt::format("fleetmap-bench-capacity-{}", index);
      options.discovery_server = discovery_server;
      Group group;
      FLEETMAP_ASSIGN_OR_RETURN(group.participant, transport::Participant::Create(options));
      FLEETMAP_ASSIGN_OR_RETURN(group.status,
                                transport::RobotStatusWriter::Create(*group.participant));
      FLEETMAP_ASSIGN_OR_RETURN(group.tiles, transport::VectorTileWriter::Create(
                                                 *group.participant, transport::kRobotTilesTopic));
      for (int robot = index; robot < robots; robot += participants) group.robots.push_back(robot);
      self->groups_.push_back(std::move(group));
    }
    self->robots_ = robots;
    return self;
  }

  int participants() const { return static_cast<int>(groups_.size()); }

  ~LoadGenerator() {
    for (Group& group : groups_) {
      std::vector<RobotId> ids;
      for (const int robot : group.robots) ids.push_back(Id(robot));
      (void)group.status->Leave(ids);
      group.tiles.reset();
      group.status.reset();
      group.participant.reset();
    }
  }

  static RobotId Id(int robot) { return RobotId{fmt::format("robot{}", robot)}; }
  // Where robot `robot`'s building sits, in tiles.
  std::pair<int, int> BuildingOffset(int robot) const {
    const int building = robot / kRobotsPerBuilding;
    return {kColumnOfBuilding[building % kBuildingsPerRow] * stream_.tiles_wide,
            (building / kBuildingsPerRow) * stream_.tiles_high};
  }

  // Sends what is due at `now`: each robot one update every 1/rate s, staggered.
  void Tick(SteadyClock::time_point now) {
    const auto period = std::chrono::duration_cast<SteadyClock::duration>(
        std::chrono::duration<double>(1.0 / rate_));
    if (start_ == SteadyClock::time_point{}) start_ = now;
    for (Group& group : groups_) {
      for (const int robot : group.robots) {
        auto& next = next_update_[robot];
        if (next == SteadyClock::time_point{}) next = start_ + period * robot / robots_;
        if (now < next) continue;
        next += period;
        Send(group, robot);
      }
    }
  }

  uint64_t tiles_sent() const { return tiles_sent_; }

 private:
  struct Group {
    std::unique_ptr<transport::Participant> participant;
    std::unique_ptr<transport::RobotStatusWriter> status;
    std::unique_ptr<transport::VectorTileWriter> tiles;
    std::vector<int> robots;
  };

  LoadGenerator(const TileStream& stream, double rate) : stream_(stream), rate_(rate) {}

  void Send(Group& group, int robot) {
    const int steps = static_cast<int>(stream_.steps.size());
    int& sent = updates_[robot];
    // Each robot of a building starts at its own phase; past the last step it starts over, its
    // map revealed again from the first column (a new run through the same building).
    const int phase = (robot % kRobotsPerBuilding) * steps / kRobotsPerBuilding;
    const int step = (phase + sent) % steps;
    ++sent;
    const auto [dx, dy] = BuildingOffset(robot);
    const Timestamp stamp = Clock::now();
    RobotStatus status;
    status.robot = Id(robot);
    status.stamp = stamp;
    status.map_resolution = 0.05;
    status.map_revision = static_cast<uint32_t>(sent);
    status.fleet_from_map_given = true;
    status.sequence_number = static_cast<uint32_t>(sent);
    (void)group.status->Write(status);
    const auto& changed = stream_.steps[static_cast<size_t>(step)];
    for (const auto& [tile, map] : changed) {
      transport::VectorTileMessage message;
      message.robot_id = Id(robot);
      message.tile = TileId{tile.x + dx, tile.y + dy};
      message.revision = ++revisions_[{robot, message.tile}];
      message.stamp = stamp;
      message.tile_size = kTileSize;
      message.map = ShiftedByTiles(map, dx, dy);
      if (group.tiles->Write(message).ok()) ++tiles_sent_;
    }
  }

  const TileStream& stream_;
  double rate_;
  int robots_ = 0;
  std::vector<Group> groups_;
  SteadyClock::time_point start_{};
  std::map<int, SteadyClock::time_point> next_update_;
  std::map<int, int> updates_;
  std::map<std::pair<int, TileId>, uint32_t> revisions_;
  uint64_t tiles_sent_ = 0;
};

// The shard file of a stage with `shards` servers: strips of whole building columns, the outer
// ones reaching far beyond the buildings (no tile on no region).
StatusOr<std::string> WriteShardFile(const CapacityArgs& args, const TileStream& stream,
                                     int shards) {
  const double column = stream.tiles_wide * kTileSize;
  const int columns_per_shard = kBuildingsPerRow / shards;
  constexpr double kBeyond = 1e6;
  std::string yaml = "shards:\n";
  for (int i = 0; i < shards; ++i) {
    yaml += fmt::format("  shard{}: [{}, {}, {}, {}]\n", i,
                        i == 0 ? -kBeyond : i * columns_per_shard * column, -kBeyond,
                        i == shards - 1 ? kBeyond : (i + 1) * columns_per_shard * column, kBeyond);
  }
  const std::string path = fmt::format("{}/shards-{}.yaml", args.out_dir, shards);
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(path, yaml));
  return path;
}

StatusOr<StageOutcome> RunStage(const CapacityArgs& args, int robots, const TileStream& stream,
                                const std::string& bin, bool discovery_server, int shards) {
  const auto binary = [&](const std::string& name, const std::string& subdir) {
    const std::string side_by_side = bin + name;
    return fs::exists(side_by_side) ? side_by_side : bin + subdir + "/" + name;
  };
  const int domain = process::RandomDomainId();
  std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                            {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  // A Fast DDS discovery server of its own (server id 0), on a port no other stage uses. The
  // server's own binary, not the `fastdds discovery` wrapper: a signal to the wrapper (Python)
  // leaves its child running, and the CPU measured must be the server's.
  std::unique_ptr<process::Subprocess> discovery;
  std::string discovery_list;
  if (discovery_server) {
    const int port = 11811 + domain;
    discovery_list = fmt::format("127.0.0.1:{}", port);
    discovery = std::make_unique<process::Subprocess>(
        std::vector<std::string>{"/usr/bin/fast-discovery-server", "-i", "0", "-l", "127.0.0.1",
                                 "-p", std::to_string(port)});
    if (!discovery->WaitForOutput("Server is running", seconds(20))) {
      return UnavailableError("the Fast DDS discovery server did not start: " +
                              discovery->Output());
    }
    env["ROS_DISCOVERY_SERVER"] = discovery_list;
  }
  std::string shard_file;
  if (shards > 1) {
    FLEETMAP_ASSIGN_OR_RETURN(shard_file, WriteShardFile(args, stream, shards));
  }
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  std::vector<std::unique_ptr<process::Subprocess>> servers;
  for (int shard = 0; shard < shards; ++shard) {
    const std::string store =
        fmt::format("{}/server-{}-{}-{}of{}.db", args.out_dir, robots,
                    discovery_server ? "server" : "simple", shard + 1, shards);
    std::error_code error;
    fs::remove(store, error);
    std::vector<std::string> argv;
    if (args.server_core >= 0) {
      argv = {"/usr/bin/taskset", "-c", std::to_string((args.server_core + shard) % cores)};
    }
    for (const std::string& arg :
         {binary("fleetmap-server", "server"), std::string("--store"), store,
          std::string("--no-object-learning"), std::string("--no-extrapolation"),
          std::string("--max-robots-per-participant"), std::to_string(kRobotsPerParticipant)}) {
      argv.push_back(arg);
    }
    if (shards > 1) {
      for (const std::string& arg : {std::string("--shards"), shard_file, std::string("--shard"),
                                     fmt::format("shard{}", shard)}) {
        argv.push_back(arg);
      }
    }
    servers.push_back(std::make_unique<process::Subprocess>(std::move(argv), env));
    if (!servers.back()->WaitForOutput("listening", seconds(30))) {
      return UnavailableError("fleetmap-server did not start: " + servers.back()->Output());
    }
  }
  // Every server follows every robot's status; a robot has joined once all of them say so.
  const auto joined_everywhere = [&] {
    size_t fewest = std::numeric_limits<size_t>::max();
    for (const auto& server : servers)
      fewest = std::min(fewest, CountOf(server->StdOut(), " joined ("));
    return fewest;
  };
  const auto cpu_seconds = [&] {
    std::vector<double> each;
    for (const auto& server : servers) each.push_back(CpuSeconds(server->pid()).value_or(0.0));
    return each;
  };

  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  options.name = "fleetmap-bench-capacity-reader";
  options.discovery_server = discovery_list;
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<transport::Participant> reader_participant,
                            transport::Participant::Create(options));
  auto wake_up = std::make_shared<WakeUp>();
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<transport::VectorTileReader> fused,
                            transport::VectorTileReader::Create(
                                *reader_participant, transport::kFusedTilesTopic, wake_up));
  const std::optional<uint64_t> loopback_at_start = LoopbackBytesSent();
  const std::optional<double> own_cpu_at_start = CpuSeconds(getpid());
  const std::optional<double> discovery_cpu_at_start =
      discovery ? CpuSeconds(discovery->pid()) : std::nullopt;
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<LoadGenerator> generator,
                            LoadGenerator::Create(domain, robots, args.robots_per_participant,
                                                  stream, args.rate, discovery_list));

  // Every building's tiles: a building is fused once a fused tile inside it arrived.
  std::set<std::pair<int, int>> buildings_waiting;
  for (int robot = 0; robot < robots; robot += kRobotsPerBuilding) {
    buildings_waiting.insert(generator->BuildingOffset(robot));
  }
  const auto building_of = [&](const TileId& tile) {
    return std::pair<int, int>{tile.x - tile.x % stream.tiles_wide,
                               tile.y - tile.y % stream.tiles_high};
  };

  StageOutcome outcome;
  outcome.robots = robots;
  outcome.participants = generator->participants();
  outcome.discovery = discovery_server ? "server" : "simple";
  outcome.shards = shards;
  const auto started = SteadyClock::now();
  std::optional<SteadyClock::time_point> measuring_since;
  std::vector<double> cpu_at_start;
  uint64_t sent_at_start = 0;
  uint64_t fused_since = 0;
  std::vector<double> latencies;
  NewRevisions new_revisions;  // each fused revision is timed once
  // A minute, or longer for many participants (each one's discovery takes its time).
  const auto join_limit = seconds(std::max(60, outcome.participants / 2));
  // How many robots the server says joined: discovery and the status's claim, done.
  size_t joined_robots = 0;
  SteadyClock::time_point next_log_check{};
  while (true) {
    const auto now = SteadyClock::now();
    generator->Tick(now);
    if (!measuring_since && now >= next_log_check) {
      next_log_check = now + milliseconds(250);
      joined_robots = joined_everywhere();
    }
    wake_up->WaitFor(milliseconds(5));
    for (const transport::TileEvent& event : fused->Drain()) {
      if (event.kind != transport::TileEvent::Kind::kTile) continue;
      buildings_waiting.erase(building_of(event.tile.tile));
      if (!new_revisions.Take(event.tile.tile, event.tile.revision)) continue;
      if (measuring_since) {
        ++fused_since;
        latencies.push_back(
            std::chrono::duration<double, std::milli>(event.received - event.tile.stamp).count());
      }
    }
    const bool joined = buildings_waiting.empty() && joined_robots >= static_cast<size_t>(robots);
    if (joined && !outcome.joined_s) {
      outcome.joined_s = std::chrono::duration<double>(now - started).count();
      if (const auto bytes = LoopbackBytesSent(); bytes && loopback_at_start) {
        outcome.join_mb = static_cast<double>(*bytes - *loopback_at_start) / 1e6;
      }
      if (const auto cpu = CpuSeconds(getpid()); cpu && own_cpu_at_start) {
        outcome.participants_cpu_s = *cpu - *own_cpu_at_start;
      }
      if (discovery_cpu_at_start) {
        if (const auto cpu = CpuSeconds(discovery->pid())) {
          outcome.discovery_server_cpu_s = *cpu - *discovery_cpu_at_start;
        }
      }
    }
    const bool settled =
        outcome.joined_s &&
        now - started >= std::chrono::duration<double>(*outcome.joined_s + args.settle_s);
    if (!measuring_since && (settled || now - started > join_limit)) {
      measuring_since = now;
      cpu_at_start = cpu_seconds();
      sent_at_start = generator->tiles_sent();
      std::cerr << fmt::format(
          "  {} robots, {} discovery, {} server(s): {}; measuring {:.0f} s\n", robots,
          outcome.discovery, shards,
          outcome.joined_s ? fmt::format("all fused after {:.1f} s", *outcome.joined_s)
                           : fmt::format("{} of {} joined after {} s", joined_robots, robots,
                                         std::chrono::duration_cast<seconds>(join_limit).count()),
          args.stage_s);
    }
    if (measuring_since && now - *measuring_since >= std::chrono::duration<double>(args.stage_s)) {
      break;
    }
  }
  const double window =
      std::chrono::duration<double>(SteadyClock::now() - *measuring_since).count();
  outcome.offered_per_s = static_cast<double>(generator->tiles_sent() - sent_at_start) / window;
  outcome.fused_per_s = static_cast<double>(fused_since) / window;
  outcome.latencies = latencies.size();
  outcome.p50_ms = Percentile(latencies, 0.50);
  outcome.p99_ms = Percentile(latencies, 0.99);
  const std::vector<double> cpu_at_end = cpu_seconds();
  for (size_t i = 0; i < servers.size(); ++i) {
    const double cores_used = (cpu_at_end[i] - cpu_at_start.at(i)) / window;
    outcome.shard_cores.push_back(cores_used);
    outcome.server_cores += cores_used;
    outcome.server_rss_mb += StatusMb(servers[i]->pid(), "VmRSS").value_or(0.0);
    outcome.server_peak_mb += StatusMb(servers[i]->pid(), "VmHWM").value_or(0.0);
  }
  generator.reset();
  fused.reset();
  reader_participant.reset();
  for (auto& server : servers) server->Signal(SIGINT);
  for (auto& server : servers) server->Wait(seconds(60));
  if (discovery) {
    discovery->Signal(SIGINT);
    discovery->Wait(seconds(10));
  }
  return outcome;
}

int RunBenchCapacity(const CapacityArgs& args) {
  const auto fail = [](const std::string& message, int code) {
    std::cerr << "fleetmap bench capacity: " << message << "\n";
    return code;
  };
  StatusOr<std::string> bin = FindFleetBinaries();
  if (!bin.ok()) return fail(bin.status().message(), 1);
  std::error_code error;
  fs::create_directories(args.out_dir, error);
  if (error) return fail(args.out_dir + ": " + error.message(), cli::kExitBadInput);
  StatusOr<grid::OccupancyGrid> building = Building(args);
  if (!building.ok()) return fail(building.status().message(), cli::kExitBadInput);
  std::cerr << fmt::format("recording the tile stream: {} x {} cells in {} steps\n",
                           building->width(), building->height(), args.steps);
  StatusOr<TileStream> stream = RecordStream(*building, args.steps);
  if (!stream.ok()) return fail(stream.status().message(), 1);
  // The load generator keeps to the other core, so that the server's core is the server's.
  if (args.server_core >= 0) {
    cpu_set_t others;
    CPU_ZERO(&others);
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    for (long core = 0; core < cores; ++core) {
      if (core != args.server_core) CPU_SET(core, &others);
    }
    if (CPU_COUNT(&others) > 0) sched_setaffinity(0, sizeof(others), &others);
  }

  std::vector<bool> discovery_servers;
  if (args.discovery != "server") discovery_servers.push_back(false);
  if (args.discovery != "simple") discovery_servers.push_back(true);
  std::vector<StageOutcome> outcomes;
  for (const int robots : args.robots) {
    for (const bool discovery_server : discovery_servers) {
      for (const int shards : args.shards) {
        std::cerr << fmt::format("{} robots at {} updates/s each, {} discovery, {} server(s)\n",
                                 robots, args.rate, discovery_server ? "server" : "simple", shards);
        StatusOr<StageOutcome> outcome =
            RunStage(args, robots, *stream, *bin, discovery_server, shards);
        if (!outcome.ok()) return fail(outcome.status().message(), 1);
        outcomes.push_back(*outcome);
      }
    }
  }

  nlohmann::json json = nlohmann::json::array();
  std::string csv =
      "robots,participants,discovery,shards,offered_tiles_per_s,fused_tiles_per_s,p50_ms,p99_ms,"
      "latencies,joined_s,join_mb,participants_cpu_s,discovery_server_cpu_s,server_cores,"
      "shard_cores,server_rss_mb,server_peak_mb\n";
  fmt::print("\nfleet capacity of one server core{}: robots explore at {} updates/s each ({})\n",
             args.server_core >= 0 ? fmt::format(" (core {})", args.server_core) : "", args.rate,
             args.map_path.empty() ? fmt::format("a {:.0f} m simulated office", args.size)
                                   : args.map_path);
  fmt::print(
      "{:>7} {:>6} {:>10} {:>7} {:>10} {:>10} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>6} {:>12} "
      "{:>7} {:>8}\n",
      "robots", "parts", "discovery", "shards", "offered/s", "fused/s", "p50 ms", "p99 ms",
      "joined s", "join MB", "parts s", "disc. s", "cores", "per shard", "RSS MB", "peak MB");
  std::map<std::pair<std::string, int>, int> largest;
  for (const StageOutcome& o : outcomes) {
    std::string per_shard;
    for (const double cores : o.shard_cores) {
      per_shard += (per_shard.empty() ? "" : "+") + Fixed(cores, 2);
    }
    const auto shown = [](const std::optional<double>& v, int decimals) {
      return v ? Fixed(*v, decimals) : std::string("-");
    };
    fmt::print(
        "{:>7} {:>6} {:>10} {:>7} {:>10} {:>10} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>6} {:>12} "
        "{:>7} {:>8}\n",
        o.robots, o.participants, o.discovery, o.shards, Fixed(o.offered_per_s, 0),
        Fixed(o.fused_per_s, 0), Fixed(o.p50_ms, 1), Fixed(o.p99_ms, 1), shown(o.joined_s, 1),
        shown(o.join_mb, 1), shown(o.participants_cpu_s, 1), shown(o.discovery_server_cpu_s, 2),
        Fixed(o.server_cores, 2), o.shards > 1 ? per_shard : "-", Fixed(o.server_rss_mb, 0),
        Fixed(o.server_peak_mb, 0));
    if (o.p99_ms <= kP99TargetMs && o.joined_s && o.latencies > 0) {
      largest[{o.discovery, o.shards}] = o.robots;
    }
    const auto optional = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    json.push_back({{"robots", o.robots},
                    {"participants", o.participants},
                    {"discovery", o.discovery},
                    {"shards", o.shards},
                    {"shard_cores", o.shard_cores},
                    {"offered_tiles_per_s", o.offered_per_s},
                    {"fused_tiles_per_s", o.fused_per_s},
                    {"p50_ms", o.p50_ms},
                    {"p99_ms", o.p99_ms},
                    {"latencies", o.latencies},
                    {"joined_s", optional(o.joined_s)},
                    {"join_mb", optional(o.join_mb)},
                    {"participants_cpu_s", optional(o.participants_cpu_s)},
                    {"discovery_server_cpu_s", optional(o.discovery_server_cpu_s)},
                    {"server_cores", o.server_cores},
                    {"server_rss_mb", o.server_rss_mb},
                    {"server_peak_mb", o.server_peak_mb}});
    const auto cell = [](const std::optional<double>& v) {
      return v ? Fixed(*v, 3) : std::string();
    };
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", o.robots,
                       o.participants, o.discovery, o.shards, Fixed(o.offered_per_s, 1),
                       Fixed(o.fused_per_s, 1), Fixed(o.p50_ms, 2), Fixed(o.p99_ms, 2), o.latencies,
                       cell(o.joined_s), cell(o.join_mb), cell(o.participants_cpu_s),
                       cell(o.discovery_server_cpu_s), Fixed(o.server_cores, 3), per_shard,
                       Fixed(o.server_rss_mb, 1), Fixed(o.server_peak_mb, 1));
  }
  for (const bool discovery_server : discovery_servers) {
    const std::string kind = discovery_server ? "server" : "simple";
    for (const int shards : args.shards) {
      const auto it = largest.find({kind, shards});
      fmt::print("largest fleet with fusion p99 <= {:.0f} ms ({} discovery, {} server(s)): {}\n",
                 kP99TargetMs, kind, shards,
                 it != largest.end() ? std::to_string(it->second) + " robots" : "none");
    }
  }
  fmt::print(
      "(latency: a robot tile's stamp to the fused tile on a reader; offered: robot tiles "
      "sent; fused: fused tile updates received)\n");
  if (const Status written = WriteFileAtomically(args.out_dir + "/capacity.json", json.dump(2));
      !written.ok()) {
    return fail(written.message(), 1);
  }
  if (const Status written = WriteFileAtomically(args.out_dir + "/capacity.csv", csv);
      !written.ok()) {
    return fail(written.message(), 1);
  }
  fmt::print("CSV and JSON: {}/capacity.csv, {}/capacity.json\n", args.out_dir, args.out_dir);
  return cli::kExitOk;
}

}  // namespace

void AddBenchCapacityCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<CapacityArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "capacity", "How many exploring robots one server core holds");
  command->add_option("--robots", args->robots, "fleet sizes, one stage each")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  command->add_option("--stage", args->stage_s, "measured seconds per fleet size")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  command->add_option("--settle", args->settle_s, "seconds from the join to the measurement")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  command->add_option("--rate", args->rate, "updates per second per robot")
      ->check(CLI::Range(0.05, 50.0))
      ->capture_default_str();
  command->add_option("--map", args->map_path,
                      "a ROS map_server YAML whose map the robots explore (default: a simulated "
                      "office of --size)");
  command->add_option("--size", args->size, "the simulated office's side, metres")
      ->check(CLI::Range(10.0, 200.0))
      ->capture_default_str();
  command->add_option("--steps", args->steps, "steps in which a building is revealed")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  command
      ->add_option("--server-core", args->server_core,
                   "the core the server is pinned to (taskset); -1: not pinned")
      ->check(CLI::Range(-1, 1023))
      ->capture_default_str();
  command
      ->add_option("--discovery", args->discovery,
                   "simple discovery, a Fast DDS discovery server (`fastdds discovery`), or both "
                   "at each fleet size")
      ->check(CLI::IsMember({"simple", "server", "both"}))
      ->capture_default_str();
  command
      ->add_option(
          "--shards", args->shards,
          "shard servers per stage, each fusing a strip of the buildings (docs/shards.md), "
          "shard i on core --server-core + i (1, 2, 4 or 8; one stage each)")
      ->check(CLI::IsMember({1, 2, 4, 8}))
      ->capture_default_str();
  command
      ->add_option("--robots-per-participant", args->robots_per_participant,
                   "robots per load-generator participant (1: a participant per robot, as agents "
                   "are; how discovery grows with participants)")
      ->check(CLI::Range(1, kRobotsPerParticipant))
      ->capture_default_str();
  command->add_option("--out", args->out_dir, "where the stores, CSV and JSON go")
      ->capture_default_str();
  command->callback([args, exit_code] { *exit_code = RunBenchCapacity(*args); });
}

}  // namespace fleetmap::bench
