#include "bench/fleet/bench_failover_command.hpp"

#include <fmt/format.h>
#include <signal.h>

#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "bench/fleet/fleet_sim.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/wake_up.hpp"
#include "common/process/subprocess.hpp"
#include "common/sim/terrain.hpp"
#include "common/store/map_store.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/tile_payload.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/vector_map/rasterizer.hpp"

namespace fleetmap::bench {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

struct FailoverArgs {
  int robots = 8;
  int runs = 10;
  std::string terrain = "office";
  double size = 40.0;
  uint32_t seed = 1;
  double warmup_s = 10.0;  // robots explore this long before the kill
  double after_s = 8.0;    // and this long after it
  std::string out_dir = "out/bench-failover";
};

struct RunOutcome {
  int run = 0;
  // From the kill to what a reader got from the standby.
  std::optional<double> tiles_ms;    // its first fused tile that the primary had written
  std::optional<double> map_ms;      // its first rt/fleetmap/map
  std::optional<double> frames_ms;   // its first robot frame
  std::optional<double> serving_ms;  // its rt/fleetmap/servers sample that says it serves
  size_t reader_tiles = 0;           // fused tiles the reader holds at the end
  size_t reader_stale = 0;           // of them, not the standby's last revision
  size_t store_tiles = 0;            // fused tiles in the standby's store
  size_t identical_tiles = 0;        // byte-identical to the reference server's
  size_t missing_tiles = 0;          // in one store only
  size_t differing_cells = 0;        // cells of the tiles that are not identical
};

double MsSince(Timestamp from, Timestamp to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

// The bench's reader of the fleet: served topics as every fleetmap reader reads them.
class FailoverWatcher {
 public:
  struct FusedTile {
    std::string writer;
    uint32_t revision = 0;
  };

  static StatusOr<std::unique_ptr<FailoverWatcher>> Create(int domain) {
    std::unique_ptr<FailoverWatcher> self(new FailoverWatcher());
    transport::ParticipantOptions options;
    options.domain_id = domain;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    options.name = "fleetmap-bench-failover";
    FLEETMAP_ASSIGN_OR_RETURN(self->participant_, transport::Participant::Create(options));
    transport::Participant& participant = *self->participant_;
    FLEETMAP_ASSIGN_OR_RETURN(
        self->tiles_, transport::VectorTileReader::Create(participant, transport::kFusedTilesTopic,
                                                          self->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(
        self->maps_, transport::OccupancyGridReader::Create(participant, transport::kFleetMapTopic,
                                                            self->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(self->frames_,
                              transport::RobotFrameReader::Create(participant, self->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(self->servers_,
                              transport::FleetServerReader::Create(participant, self->wake_up_));
    return self;
  }

  ~FailoverWatcher() {
    tiles_.reset();
    maps_.reset();
    frames_.reset();
    servers_.reset();
    participant_.reset();
  }

  // Drains the readers for `how_long`, or until `done`.
  void Follow(std::chrono::milliseconds how_long, const std::function<bool()>& done = nullptr) {
    const auto until = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < until) {
      wake_up_->WaitFor(milliseconds(20));
      Drain();
      if (done && done()) return;
    }
  }

  // From now on, the first samples of the server named `standby` are timed from `killed_at`.
  void TimeFailover(const std::string& standby, Timestamp killed_at) {
    standby_ = standby;
    killed_at_ = killed_at;
  }

  const std::optional<transport::FleetServerMessage> Server(const std::string& name) const {
    const auto it = servers_by_name_.find(name);
    return it == servers_by_name_.end() ? std::nullopt : std::optional(it->second);
  }
  bool Serving(const std::string& name) const {
    const auto server = Server(name);
    return server && server->serving;
  }
  const std::map<TileId, FusedTile>& fused() const { return fused_; }
  std::string IdOf(const std::string& name) const {
    const auto server = Server(name);
    return server ? server->server_id : std::string("?");
  }
  void Record(RunOutcome* outcome) const {
    outcome->tiles_ms = tiles_ms_;
    outcome->map_ms = map_ms_;
    outcome->frames_ms = frames_ms_;
    outcome->serving_ms = serving_ms_;
  }

 private:
  FailoverWatcher() = default;

  bool FromStandby(const std::string& writer) const {
    return killed_at_ && writer.rfind(IdOf(standby_), 0) == 0;
  }
  void Since(std::optional<double>* first, Timestamp at) const {
    if (killed_at_ && !*first && at > *killed_at_) *first = MsSince(*killed_at_, at);
  }

  void Drain() {
    const Timestamp now = Clock::now();
    for (transport::TileEvent& event : tiles_->Drain()) {
      if (event.kind != transport::TileEvent::Kind::kTile) continue;
      FusedTile& held = fused_[event.tile.tile];
      // A tile only the standby wrote (new since the kill) is taken from anyone; what times the
      // failover is a tile the killed server owned.
      const bool taken_over = !held.writer.empty() && !FromStandby(held.writer);
      if (FromStandby(event.writer) && taken_over) Since(&tiles_ms_, event.received);
      held = FusedTile{event.writer, event.tile.revision};
    }
    for (StatusOr<transport::MapMessage>& map : maps_->Drain()) {
      // The killed server sent nothing after the kill: a map from later is the standby's.
      if (map.ok() && killed_at_ && now - *killed_at_ > milliseconds(100)) Since(&map_ms_, now);
    }
    for (const transport::RobotFrameEvent& event : frames_->Drain()) {
      if (FromStandby(event.writer)) Since(&frames_ms_, now);
    }
    for (const transport::FleetServerEvent& event : servers_->Drain()) {
      if (event.kind != transport::FleetServerEvent::Kind::kSample) continue;
      servers_by_name_[event.message.name] = event.message;
      if (event.message.name == standby_ && event.message.serving) Since(&serving_ms_, now);
    }
  }

  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::VectorTileReader> tiles_;
  std::unique_ptr<transport::OccupancyGridReader> maps_;
  std::unique_ptr<transport::RobotFrameReader> frames_;
  std::unique_ptr<transport::FleetServerReader> servers_;
  std::map<TileId, FusedTile> fused_;
  std::map<std::string, transport::FleetServerMessage> servers_by_name_;
  std::string standby_;
  std::optional<Timestamp> killed_at_;
  std::optional<double> tiles_ms_, map_ms_, frames_ms_, serving_ms_;
};

StatusOr<std::map<TileId, store::TileRecord>> FusedTilesIn(const std::string& path) {
  store::StoreOptions options;
  options.verify_on_open = false;
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<store::MapStore> store,
                            store::MapStore::Open(path, options));
  FLEETMAP_ASSIGN_OR_RETURN(std::vector<store::TileRecord> tiles,
                            store->LatestTiles(store::TileOwner::Fleet()));
  std::map<TileId, store::TileRecord> out;
  for (store::TileRecord& tile : tiles) out[tile.tile] = std::move(tile);
  return out;
}

// Cells of two fused tiles' payloads that rasterize differently.
StatusOr<size_t> DifferingCells(const store::TileRecord& a, const store::TileRecord& b) {
  FLEETMAP_ASSIGN_OR_RETURN(transport::VectorTileMessage first,
                            transport::DecodeTilePayload(a.payload, "standby's fused tile"));
  FLEETMAP_ASSIGN_OR_RETURN(transport::VectorTileMessage second,
                            transport::DecodeTilePayload(b.payload, "reference's fused tile"));
  constexpr double kResolution = 0.05;
  const int side = static_cast<int>(std::lround(first.tile_size / kResolution));
  const Pose2 origin{a.tile.x * first.tile_size, a.tile.y * first.tile_size, 0.0};
  const vector_map::Rasterizer rasterizer;
  FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid one,
                            rasterizer.Rasterize(first.map, side, side, kResolution, origin));
  FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid two,
                            rasterizer.Rasterize(second.map, side, side, kResolution, origin));
  size_t differing = 0;
  for (size_t i = 0; i < one.data().size(); ++i) differing += one.data()[i] != two.data()[i];
  return differing;
}

// The standby's fused tiles against the reference server's, from their stores.
Status CompareStores(const std::string& standby, const std::string& reference,
                     RunOutcome* outcome) {
  FLEETMAP_ASSIGN_OR_RETURN(auto mine, FusedTilesIn(standby));
  FLEETMAP_ASSIGN_OR_RETURN(auto theirs, FusedTilesIn(reference));
  outcome->store_tiles = mine.size();
  for (const auto& [tile, record] : mine) {
    const auto other = theirs.find(tile);
    if (other == theirs.end()) {
      ++outcome->missing_tiles;
    } else if (other->second.payload == record.payload) {
      ++outcome->identical_tiles;
    } else {
      FLEETMAP_ASSIGN_OR_RETURN(size_t cells, DifferingCells(record, other->second));
      outcome->differing_cells += cells;
    }
  }
  for (const auto& [tile, record] : theirs) outcome->missing_tiles += mine.count(tile) == 0;
  return Status::Ok();
}

StatusOr<RunOutcome> RunOnce(const FailoverArgs& args, int run, const std::string& bin) {
  const auto binary = [&](const std::string& name, const std::string& subdir) {
    const std::string side_by_side = bin + name;
    return fs::exists(side_by_side) ? side_by_side : bin + subdir + "/" + name;
  };
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  const std::string dir = fmt::format("{}/run{}", args.out_dir, run);
  std::error_code error;
  fs::remove_all(dir, error);
  fs::create_directories(dir, error);
  if (error) return InvalidArgumentError(dir + ": " + error.message());
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<FailoverWatcher> watcher,
                            FailoverWatcher::Create(domain));
  const auto server = [&](const std::string& name, int strength) {
    return std::make_unique<process::Subprocess>(
        std::vector<std::string>{binary("fleetmap-server", "server"), "--name", name,
                                 "--ownership-strength", std::to_string(strength), "--store",
                                 dir + "/" + name + ".db", "--map-period", "0.2",
                                 "--no-object-learning", "--no-extrapolation"},
        env);
  };
  auto primary = server("primary", 100);
  auto standby = server("standby", 50);
  auto reference = server("reference", 10);
  watcher->Follow(seconds(30), [&] {
    return watcher->Serving("primary") && watcher->Server("standby") &&
           watcher->Server("reference");
  });
  if (!watcher->Serving("primary") || watcher->Serving("standby")) {
    return UnavailableError("the servers did not settle (primary serving, standby standing by): " +
                            primary->Output() + standby->Output());
  }
  std::vector<std::unique_ptr<process::Subprocess>> agents;
  for (int i = 0; i < args.robots; ++i) {
    agents.push_back(std::make_unique<process::Subprocess>(
        std::vector<std::string>{
            binary("fleetmap-agent", "robot_agent"), "--robot-id", "robot" + std::to_string(i),
            "--sim", args.terrain, "--sim-size", fmt::format("{}", args.size), "--sim-seed",
            std::to_string(args.seed + static_cast<uint32_t>(run)), "--sim-robot-index",
            std::to_string(i), "--sim-robots", std::to_string(args.robots)},
        env));
  }
  watcher->Follow(milliseconds(static_cast<int64_t>(args.warmup_s * 1000)));

  const Timestamp killed_at = Clock::now();
  primary->Signal(SIGKILL);
  watcher->TimeFailover("standby", killed_at);
  primary->Wait(seconds(10));
  watcher->Follow(milliseconds(static_cast<int64_t>(args.after_s * 1000)));

  // The robots stop; what they sent last settles on both servers and the reader.
  for (auto& agent : agents) agent->Signal(SIGINT);
  for (auto& agent : agents) agent->Wait(seconds(20));
  watcher->Follow(seconds(4));
  RunOutcome outcome;
  outcome.run = run;
  watcher->Record(&outcome);
  // Every fused tile the reader holds must be the standby's, at its last revision: the standby's
  // store says which that is.
  standby->Signal(SIGINT);
  reference->Signal(SIGINT);
  const std::optional<int> standby_exit = standby->Wait(seconds(60));
  const std::optional<int> reference_exit = reference->Wait(seconds(60));
  if (standby_exit != 0 || reference_exit != 0) {
    return UnavailableError("a server did not stop cleanly: " + standby->Output() +
                            reference->Output());
  }
  FLEETMAP_ASSIGN_OR_RETURN(auto standby_tiles, FusedTilesIn(dir + "/standby.db"));
  const std::string standby_id = watcher->IdOf("standby");
  for (const auto& [tile, held] : watcher->fused()) {
    ++outcome.reader_tiles;
    const auto stored = standby_tiles.find(tile);
    const bool current = stored != standby_tiles.end() &&
                         stored->second.revision == held.revision &&
                         held.writer.rfind(standby_id, 0) == 0;
    outcome.reader_stale += current ? 0 : 1;
  }
  FLEETMAP_RETURN_IF_ERROR(CompareStores(dir + "/standby.db", dir + "/reference.db", &outcome));
  return outcome;
}

std::string OptionalMs(const std::optional<double>& ms) {
  return ms ? Fixed(*ms, 0) : std::string("-");
}

int RunBenchFailover(const FailoverArgs& args) {
  const auto fail = [](const std::string& message, int code) {
    std::cerr << "fleetmap bench failover: " << message << "\n";
    return code;
  };
  if (!sim::TerrainKindFromName(args.terrain)) {
    return fail("--terrain \"" + args.terrain + "\" is not a terrain kind", cli::kExitBadInput);
  }
  StatusOr<std::string> bin = FindFleetBinaries();
  if (!bin.ok()) return fail(bin.status().message(), 1);
  std::vector<RunOutcome> outcomes;
  for (int run = 0; run < args.runs; ++run) {
    std::cerr << fmt::format("run {}/{}: {} robots, primary killed after {:.0f} s\n", run + 1,
                             args.runs, args.robots, args.warmup_s);
    StatusOr<RunOutcome> outcome = RunOnce(args, run, *bin);
    if (!outcome.ok()) return fail(outcome.status().message(), 1);
    std::cerr << fmt::format(
        "  tiles {} ms, map {} ms, frames {} ms; reader stale {}/{}; identical {}/{}\n",
        OptionalMs(outcome->tiles_ms), OptionalMs(outcome->map_ms), OptionalMs(outcome->frames_ms),
        outcome->reader_stale, outcome->reader_tiles, outcome->identical_tiles,
        outcome->store_tiles);
    outcomes.push_back(*std::move(outcome));
  }

  nlohmann::json json = nlohmann::json::array();
  std::string csv =
      "run,tiles_ms,map_ms,frames_ms,serving_ms,reader_tiles,reader_stale,store_tiles,"
      "identical_tiles,missing_tiles,differing_cells\n";
  std::vector<double> tiles, maps, frames, serving;
  size_t stale = 0, identical = 0, stored = 0, missing = 0, differing = 0, unfollowed = 0;
  for (const RunOutcome& o : outcomes) {
    const auto opt = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    json.push_back({{"run", o.run},
                    {"tiles_ms", opt(o.tiles_ms)},
                    {"map_ms", opt(o.map_ms)},
                    {"frames_ms", opt(o.frames_ms)},
                    {"serving_ms", opt(o.serving_ms)},
                    {"reader_tiles", o.reader_tiles},
                    {"reader_stale", o.reader_stale},
                    {"store_tiles", o.store_tiles},
                    {"identical_tiles", o.identical_tiles},
                    {"missing_tiles", o.missing_tiles},
                    {"differing_cells", o.differing_cells}});
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", o.run,
                       o.tiles_ms ? Fixed(*o.tiles_ms, 1) : "", o.map_ms ? Fixed(*o.map_ms, 1) : "",
                       o.frames_ms ? Fixed(*o.frames_ms, 1) : "",
                       o.serving_ms ? Fixed(*o.serving_ms, 1) : "", o.reader_tiles, o.reader_stale,
                       o.store_tiles, o.identical_tiles, o.missing_tiles, o.differing_cells);
    for (auto [value, into] :
         {std::pair{&o.tiles_ms, &tiles}, std::pair{&o.map_ms, &maps},
          std::pair{&o.frames_ms, &frames}, std::pair{&o.serving_ms, &serving}}) {
      if (*value) into->push_back(**value);
    }
    unfollowed += !o.tiles_ms || !o.map_ms || !o.frames_ms;
    stale += o.reader_stale;
    identical += o.identical_tiles;
    stored += o.store_tiles;
    missing += o.missing_tiles;
    differing += o.differing_cells;
  }
  const auto stats = [](std::vector<double> v) {
    if (v.empty()) return std::string("-");
    const double most = *std::max_element(v.begin(), v.end());
    return fmt::format("{} (max {})", Fixed(Median(std::move(v)), 0), Fixed(most, 0));
  };
  fmt::print(
      "\nhot standby failover: {} runs, {} robots exploring a {:.0f} m {}, primary killed "
      "(SIGKILL) after {:.0f} s\n",
      args.runs, args.robots, args.size, args.terrain, args.warmup_s);
  fmt::print("  reader follows the standby, ms from the kill, median (max):\n");
  fmt::print("    fused tiles {}, rt/fleetmap/map {}, robot frames {}, standby says it serves {}\n",
             stats(tiles), stats(maps), stats(frames), stats(serving));
  fmt::print("  runs where a reader did not follow: {}\n", unfollowed);
  fmt::print(
      "  fused tiles the reader held at the end that were not the standby's last revision: "
      "{}\n",
      stale);
  fmt::print(
      "  standby vs the never-killed reference server (stores): {}/{} fused tiles "
      "byte-identical, {} in one store only, {} differing cells\n",
      identical, stored, missing, differing);
  if (const Status written = WriteFileAtomically(args.out_dir + "/failover.json", json.dump(2));
      !written.ok()) {
    return fail(written.message(), 1);
  }
  if (const Status written = WriteFileAtomically(args.out_dir + "/failover.csv", csv);
      !written.ok()) {
    return fail(written.message(), 1);
  }
  fmt::print("CSV and JSON: {}/failover.csv, {}/failover.json\n", args.out_dir, args.out_dir);
  return cli::kExitOk;
}

}  // namespace

void AddBenchFailoverCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<FailoverArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "failover", "A hot standby: the primary server killed while robots explore");
  command->add_option("--robots", args->robots, "simulated robots exploring")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--runs", args->runs, "runs (a new fleet each)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  command->add_option("--terrain", args->terrain, "simulated terrain")->capture_default_str();
  command->add_option("--size", args->size, "terrain side, metres")
      ->check(CLI::Range(10.0, 400.0))
      ->capture_default_str();
  command->add_option("--seed", args->seed, "terrain seed of the first run (then +1 per run)")
      ->capture_default_str();
  command->add_option("--warmup", args->warmup_s, "seconds the robots explore before the kill")
      ->check(CLI::Range(1.0, 600.0))
      ->capture_default_str();
  command->add_option("--after", args->after_s, "seconds they explore after it")
      ->check(CLI::Range(1.0, 600.0))
      ->capture_default_str();
  command->add_option("--out", args->out_dir, "where the stores, CSV and JSON go")
      ->capture_default_str();
  command->callback([args, exit_code] { *exit_code = RunBenchFailover(*args); });
}

}  // namespace fleetmap::bench
