#include "bench/fleet/bench_quarantine_command.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "bench/fleet/fleet_sim.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/wake_up.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"

namespace fleetmap::bench {
namespace {

namespace fs = std::filesystem;
using SteadyClock = std::chrono::steady_clock;
using Standing = transport::RobotFrameMessage::Standing;
using Cell = std::pair<int, int>;

// The building: 19.2 m square, walls every 6 m, all seen. `shelves` adds four shelf rows (3 m x
// 0.4 m outlines, 27 m of edges) in one room; `turn_deg` turns the whole map about its centre.
grid::OccupancyGrid Building(bool shelves, double turn_deg = 0.0) {
  constexpr int kSide = 384;
  grid::OccupancyGrid map(kSide, kSide, 0.05, Pose2{0.5, 0.5, 0.0}, grid::kFreeValue);
  const auto wall = [&](int x, int y) {
    if (x % 120 == 10 || y % 120 == 10) return true;
    if (!shelves) return false;
    for (const int y0 : {140, 160, 180, 200}) {
      const bool in_x = x >= 140 && x < 200;
      const bool in_y = y >= y0 && y < y0 + 8;
      if (in_x && in_y && (x == 140 || x == 199 || y == y0 || y == y0 + 7)) return true;
    }
    return false;
  };
  const double a = turn_deg * M_PI / 180.0;
  const double c = kSide / 2.0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const double sx = std::cos(a) * (x - c) + std::sin(a) * (y - c) + c;
      const double sy = -std::sin(a) * (x - c) + std::cos(a) * (y - c) + c;
      const int ix = static_cast<int>(std::lround(sx));
      const int iy = static_cast<int>(std::lround(sy));
      if (ix < 0 || iy < 0 || ix >= kSide || iy >= kSide) {
        map.at(x, y) = grid::kUnknownValue;
      } else if (wall(ix, iy)) {
        map.at(x, y) = grid::kOccupiedValue;
      }
    }
  }
  return map;
}

grid::OccupancyGrid AllFree() {
  grid::OccupancyGrid map = Building(false);
  std::fill(map.mutable_data().begin(), map.mutable_data().end(), grid::kFreeValue);
  return map;
}

std::set<Cell> Occupied(const grid::OccupancyGrid& grid) {
  std::set<Cell> cells;
  const int ox = static_cast<int>(std::lround(grid.origin().x / grid.resolution()));
  const int oy = static_cast<int>(std::lround(grid.origin().y / grid.resolution()));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.at(x, y) >= 65) cells.emplace(ox + x, oy + y);
    }
  }
  return cells;
}

size_t Missing(const std::set<Cell>& cells, const std::set<Cell>& in) {
  size_t missing = 0;
  for (const Cell& cell : cells) missing += in.count(cell) == 0;
  return missing;
}

double Ms(Timestamp from, Timestamp to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

struct Scenario {
  std::string name;
  std::string offender_map;
  std::vector<std::string> offender_args;
  bool confirm = false;  // a second robot with the offender's map follows
  bool established_shelves = false;
};

struct Outcome {
  std::string scenario;
  size_t established = 0;  // established wall cells
  size_t max_erased = 0;   // the most of them missing from any fused map after the offender
  bool quarantined = false;
  std::optional<double> quarantine_ms;  // offender's first tile -> its quarantine
  std::optional<double> confirm_ms;     // confirming robot's first tile -> change fused
  bool released = false;                // the offender left quarantine (confirmed change)
};

// Watches the fleet: the fused grid, the robots' frames and their first tiles.
class Watcher {
 public:
  static StatusOr<std::unique_ptr<Watcher>> Create(int domain) {
    std::unique_ptr<Watcher> self(new Watcher());
    transport::ParticipantOptions options;
    options.domain_id = domain;
    options.localhost_only = true;
    options.name = "fleetmap-bench-quarantine";
    FLEETMAP_ASSIGN_OR_RETURN(self->participant_, transport::Participant::Create(options));
    FLEETMAP_ASSIGN_OR_RETURN(self->maps_,
                              transport::OccupancyGridReader::Create(
                                  *self->participant_, transport::kFleetMapTopic, self->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(
        self->frames_, transport::RobotFrameReader::Create(*self->participant_, self->wake_up_));
    FLEETMAP_ASSIGN_OR_RETURN(
        self->tiles_, transport::VectorTileReader::Create(
                          *self->participant_, transport::kRobotTilesTopic, self->wake_up_));
    return self;
  }
  ~Watcher() {
    maps_.reset();
    frames_.reset();
    tiles_.reset();
    participant_.reset();
  }

  // Drains until `done` or the deadline; calls on_map with every fused grid.
  void Follow(SteadyClock::duration how_long, const std::function<bool()>& done,
              const std::function<void(const transport::MapMessage&)>& on_map = nullptr) {
    const auto until = SteadyClock::now() + how_long;
    while (SteadyClock::now() < until) {
      wake_up_->WaitFor(std::chrono::milliseconds(50));
      for (StatusOr<transport::MapMessage>& map : maps_->Drain()) {
        if (!map.ok()) continue;
        if (on_map) on_map(*map);
        map_ = std::move(map).value();
      }
      for (transport::RobotFrameEvent& event : frames_->Drain()) {
        if (event.kind != transport::RobotFrameEvent::Kind::kSample) continue;
        const transport::RobotFrameMessage& frame = event.message;
        if (frame.standing == Standing::kQuarantined && !quarantined_at_.count(frame.robot.value)) {
          quarantined_at_[frame.robot.value] = frame.stamp;
        }
        if (frame.standing != Standing::kQuarantined && quarantined_at_.count(frame.robot.value)) {
          released_.insert(frame.robot.value);
        }
      }
      for (transport::TileEvent& event : tiles_->Drain()) {
        if (event.kind != transport::TileEvent::Kind::kTile) continue;
        auto [it, added] = first_tile_.try_emplace(event.tile.robot_id.value, event.tile.stamp);
        if (!added) it->second = std::min(it->second, event.tile.stamp);
      }
      if (done && done()) return;
    }
  }

  const std::optional<transport::MapMessage>& map() const { return map_; }
  std::optional<Timestamp> QuarantinedAt(const std::string& robot) const {
    const auto it = quarantined_at_.find(robot);
    return it == quarantined_at_.end() ? std::nullopt : std::optional(it->second);
  }
  std::optional<Timestamp> FirstTile(const std::string& robot) const {
    const auto it = first_tile_.find(robot);
    return it == first_tile_.end() ? std::nullopt : std::optional(it->second);
  }
  bool Released(const std::string& robot) const { return released_.count(robot) > 0; }

 private:
  Watcher() = default;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::OccupancyGridReader> maps_;
  std::unique_ptr<transport::RobotFrameReader> frames_;
  std::unique_ptr<transport::VectorTileReader> tiles_;
  std::optional<transport::MapMessage> map_;
  std::map<std::string, Timestamp> quarantined_at_;
  std::set<std::string> released_;
  std::map<std::string, Timestamp> first_tile_;
};

StatusOr<Outcome> RunScenario(const Scenario& scenario, const std::string& bin,
                              const std::string& maps_dir) {
  const auto binary = [&](const std::string& name, const std::string& subdir) {
    const std::string side_by_side = bin + name;
    return fs::exists(side_by_side) ? side_by_side : bin + subdir + "/" + name;
  };
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<Watcher> watcher, Watcher::Create(domain));
  process::Subprocess server({binary("fleetmap-server", "server"), "--map-period", "0.1"}, env);
  const std::string agent = binary("fleetmap-agent", "robot_agent");
  const std::string established_map =
      maps_dir + (scenario.established_shelves ? "/shelves.yaml" : "/building.yaml");
  process::Subprocess alpha({agent, "--robot-id", "alpha", "--map", established_map}, env);
  Outcome outcome;
  outcome.scenario = scenario.name;
  std::set<Cell> established;
  watcher->Follow(std::chrono::seconds(30),
                  [&] { return watcher->map() && Occupied(watcher->map()->grid).size() > 3000; });
  if (!watcher->map()) return UnavailableError("no fused map came: " + server.Output());
  watcher->Follow(std::chrono::seconds(2), nullptr);  // alpha's map settles
  established = Occupied(watcher->map()->grid);
  outcome.established = established.size();

  const auto on_map = [&](const transport::MapMessage& map) {
    outcome.max_erased = std::max(outcome.max_erased, Missing(established, Occupied(map.grid)));
  };
  std::vector<std::string> argv = {agent, "--robot-id", "offender", "--map", scenario.offender_map};
  argv.insert(argv.end(), scenario.offender_args.begin(), scenario.offender_args.end());
  process::Subprocess offender(std::move(argv), env);
  watcher->Follow(
      std::chrono::seconds(6), [&] { return watcher->QuarantinedAt("offender").has_value(); },
      on_map);
  watcher->Follow(std::chrono::seconds(2), nullptr, on_map);
  if (const auto at = watcher->QuarantinedAt("offender")) {
    outcome.quarantined = true;
    if (const auto first = watcher->FirstTile("offender")) outcome.quarantine_ms = Ms(*first, *at);
  }
  if (scenario.confirm) {
    // What the shelves were: established cells the confirming robot's map has no wall near.
    const std::set<Cell> kept = Occupied(Building(false));
    std::set<Cell> shelves;
    for (const Cell& cell : established) {
      if (kept.count(cell) == 0) shelves.insert(cell);
    }
    process::Subprocess confirmer(
        {agent, "--robot-id", "confirmer", "--map", scenario.offender_map}, env);
    std::optional<Timestamp> changed_at;
    watcher->Follow(
        std::chrono::seconds(10), [&] { return changed_at.has_value(); },
        [&](const transport::MapMessage& map) {
          const std::set<Cell> now = Occupied(map.grid);
          if (Missing(shelves, now) >= shelves.size() * 9 / 10 && !changed_at) {
            changed_at = map.stamp;
          }
        });
    if (changed_at) {
      if (const auto first = watcher->FirstTile("confirmer")) {
        outcome.confirm_ms = Ms(*first, *changed_at);
      }
    }
    watcher->Follow(std::chrono::seconds(1), nullptr);
    outcome.released = watcher->Released("offender");
    // Established walls other than the shelves must all still stand.
    std::set<Cell> walls;
    for (const Cell& cell : established) {
      if (shelves.count(cell) == 0) walls.insert(cell);
    }
    outcome.max_erased = watcher->map() ? Missing(walls, Occupied(watcher->map()->grid)) : 0;
    confirmer.Signal(SIGTERM);
    confirmer.Wait(std::chrono::seconds(10));
  }
  offender.Signal(SIGTERM);
  alpha.Signal(SIGTERM);
  offender.Wait(std::chrono::seconds(10));
  alpha.Wait(std::chrono::seconds(10));
  server.Signal(SIGINT);
  server.Wait(std::chrono::seconds(15));
  return outcome;
}

struct BenchQuarantineArgs {
  int runs = 3;
  std::string out_dir = "out/bench-quarantine";
};

int RunBenchQuarantine(const BenchQuarantineArgs& args) {
  const auto fail = [](const std::string& message, int code) {
    std::cerr << "fleetmap bench quarantine: " << message << "\n";
    return code;
  };
  StatusOr<std::string> bin = FindFleetBinaries();
  if (!bin.ok()) return fail(bin.status().message(), 1);
  std::error_code error;
  fs::create_directories(args.out_dir + "/maps", error);
  if (error) return fail(args.out_dir + ": " + error.message(), cli::kExitBadInput);
  const std::string maps = args.out_dir + "/maps";
  for (const auto& [name, grid] :
       std::vector<std::pair<std::string, grid::OccupancyGrid>>{{"building", Building(false)},
                                                                {"shelves", Building(true)},
                                                                {"turned", Building(false, 10.0)},
                                                                {"free", AllFree()}}) {
    if (const Status saved = grid::SaveMap(grid, maps + "/" + name + ".yaml"); !saved.ok()) {
      return fail(saved.message(), 1);
    }
  }
  const std::vector<Scenario> scenarios = {
      {"fresh id, all free", maps + "/free.yaml", {}, false, false},
      {"shifted 2 m", maps + "/building.yaml", {"--fleet-from-map", "2", "0", "0"}, false, false},
      {"turned 10 degrees", maps + "/turned.yaml", {}, false, false},
      {"shelves removed, confirmed", maps + "/building.yaml", {}, true, true},
  };
  std::vector<Outcome> outcomes;
  for (int run = 0; run < args.runs; ++run) {
    for (const Scenario& scenario : scenarios) {
      std::cerr << fmt::format("run {}/{}: {}\n", run + 1, args.runs, scenario.name);
      StatusOr<Outcome> outcome = RunScenario(scenario, *bin, maps);
      if (!outcome.ok()) return fail(outcome.status().message(), 1);
      outcomes.push_back(*std::move(outcome));
    }
  }
  nlohmann::json json = nlohmann::json::array();
  std::string csv =
      "scenario,run,established_cells,max_erased,quarantined,quarantine_ms,"
      "confirm_ms,released\n";
  fmt::print("\n{:<28} {:>6} {:>12} {:>11} {:>15} {:>15}\n", "scenario", "runs", "max erased",
             "quarantined", "quarantine ms", "confirmed ms");
  for (const Scenario& scenario : scenarios) {
    size_t erased = 0, quarantined = 0, runs = 0;
    std::vector<double> to_quarantine, to_confirm;
    for (size_t i = 0; i < outcomes.size(); ++i) {
      const Outcome& o = outcomes[i];
      if (o.scenario != scenario.name) continue;
      ++runs;
      erased = std::max(erased, o.max_erased);
      quarantined += o.quarantined;
      if (o.quarantine_ms) to_quarantine.push_back(*o.quarantine_ms);
      if (o.confirm_ms) to_confirm.push_back(*o.confirm_ms);
      const auto opt = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
      };
      json.push_back({{"scenario", o.scenario},
                      {"run", i / scenarios.size()},
                      {"established_cells", o.established},
                      {"max_erased", o.max_erased},
                      {"quarantined", o.quarantined},
                      {"quarantine_ms", opt(o.quarantine_ms)},
                      {"confirm_ms", opt(o.confirm_ms)},
                      {"released", o.released}});
      csv += fmt::format("\"{}\",{},{},{},{},{},{},{}\n", o.scenario, i / scenarios.size(),
                         o.established, o.max_erased, o.quarantined ? 1 : 0,
                         o.quarantine_ms ? Fixed(*o.quarantine_ms, 1) : "",
                         o.confirm_ms ? Fixed(*o.confirm_ms, 1) : "", o.released ? 1 : 0);
    }
    const auto median = [](const std::vector<double>& v) {
      return v.empty() ? std::string("-") : Fixed(Median(v), 0);
    };
    fmt::print("{:<28} {:>6} {:>12} {:>11} {:>15} {:>15}\n", scenario.name, runs, erased,
               fmt::format("{}/{}", quarantined, runs), median(to_quarantine), median(to_confirm));
  }
  fmt::print(
      "(max erased: established wall cells missing from any fused map after the offender "
      "started; for the confirmed change, walls other than the shelves at the end; times "
      "are medians, from the robot's first tile stamp)\n");
  if (const Status written = WriteFileAtomically(args.out_dir + "/quarantine.json", json.dump(2));
      !written.ok()) {
    return fail(written.message(), 1);
  }
  if (const Status written = WriteFileAtomically(args.out_dir + "/quarantine.csv", csv);
      !written.ok()) {
    return fail(written.message(), 1);
  }
  fmt::print("CSV and JSON: {}/quarantine.csv, {}/quarantine.json\n", args.out_dir, args.out_dir);
  return cli::kExitOk;
}

}  // namespace

void AddBenchQuarantineCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchQuarantineArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "quarantine", "What one robot can do to the fleet map: quarantine of contradicting robots");
  command->add_option("--runs", args->runs, "runs of each scenario")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  command->add_option("--out", args->out_dir, "where the maps, CSV and JSON go")
      ->capture_default_str();
  command->callback([args, exit_code] { *exit_code = RunBenchQuarantine(*args); });
}

}  // namespace fleetmap::bench
