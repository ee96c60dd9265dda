#include "bench/fleet/bench_fleet_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <utility>

#include "bench/fleet/baseline_bytes.hpp"
#include "bench/fleet/fleet_scenario.hpp"
#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/fleet_sim_report.hpp"
#include "bench/report/bench_command.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/metrics/map_quality.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

struct BenchFleetArgs {
  std::vector<int> robots = {1, 4, 16};
  FleetScenarioArgs scenario{.size = 80.0};
  std::string json_path;
  // Also run one robot for robots x duration on the same terrain, and compare its map with the
  // fused map of the largest fleet: does fusing lose quality against one robot's own map?
  bool single_robot = false;
  // Also run each fleet with a hostile peer flooding the server, and report what the honest
  // robots see: latency, server memory, what the flood got in.
  bool hostile = false;
  int hostile_participants = 1;
  int hostile_ids = 1;
  // The grid wire run for real beside the tile wire, to measure its bytes side by side ("none":
  // only the baselines the tile run's agents measure).
  std::string compare_wire = "grid-updates-zstd";
  // A fleet security folder (fleetmap security) with the identities "server", robot0.. and the
  // viewer "observer": every fleet runs secured (a hostile flood then stays outside).
  std::string security_dir;
};

struct Row {
  int robots = 0;
  FleetRunResult tiles;                    // with the grid wires measured at its map changes
  std::optional<FleetRunResult> compared;  // --compare-wire, for real
  std::optional<FleetRunResult> attacked;  // tiles, with a hostile flood (--hostile)
  metrics::QualityScores quality;
};

std::string Fmt(const std::optional<double>& value, const char* unit) {
  return value ? fmt::format("{:.1f}{}", *value, unit) : std::string("n/a");
}

// The server's summary lines of the robots whose names start with `prefix`: their tiles fused and
// samples rejected, summed.
// The tile refusals the server counted by reason, from its exit summary ("refused: tiles: 12
// memory budget, 3 tile quota; ..."): honest robots are never refused, so they are the flood's.
std::string TileRefusals(const std::string& server_output) {
  constexpr std::string_view kPrefix = "refused: tiles: ";
  const size_t start = server_output.find(kPrefix);
  if (start == std::string::npos) return "none";
  const size_t from = start + kPrefix.size();
  const size_t end = server_output.find_first_of(";\n", from);
  return server_output.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

// The latencies received from `from_s` (inclusive) to `to_s` (exclusive) into the run.
std::vector<double> LatenciesBetween(const FleetRunResult& run, double from_s, double to_s) {
  std::vector<double> window;
  for (size_t i = 0; i < run.latencies_ms.size(); ++i) {
    if (run.latency_at_s[i] >= from_s && run.latency_at_s[i] < to_s) {
      window.push_back(run.latencies_ms[i]);
    }
  }
  return window;
}

// The `count` latest updates received from `from_s` to `to_s`, latest first, each as its time
// into the run and its latency: where a tail comes from (the flood's start, its end, all along).
nlohmann::json LatestBetween(const FleetRunResult& run, double from_s, double to_s, size_t count) {
  std::vector<size_t> window;
  for (size_t i = 0; i < run.latencies_ms.size(); ++i) {
    if (run.latency_at_s[i] >= from_s && run.latency_at_s[i] < to_s) window.push_back(i);
  }
  const auto later = [&](size_t a, size_t b) { return run.latencies_ms[a] > run.latencies_ms[b]; };
  std::sort(window.begin(), window.end(), later);
  window.resize(std::min(window.size(), count));
  nlohmann::json latest = nlohmann::json::array();
  for (size_t i : window) {
    latest.push_back({{"at_s", run.latency_at_s[i]}, {"ms", run.latencies_ms[i]}});
  }
  return latest;
}

// Honest robots' latency is "recovered" this long after a flood ends (issue 30's target).
constexpr double kRecoverySeconds = 5.0;

void PrintHostileTable(const std::vector<Row>& rows, const HostileAttack& attack,
                       nlohmann::json* json) {
  const HostileFloodOptions& flood = attack.flood;
  std::cout << fmt::format(
      "\nUnder a hostile flood ({} participant(s), each claiming {} robot id(s) \"{}\"...: {} "
      "heavy tiles rewritten {:.0f} times a second, and {} distinct keys spread over the ids), "
      "from {:.0f} s to {:.0f} s into the run; honest robots' fused-tile latency and the server "
      "(\"after\": from {:.0f} s after the flood ended):\n\n",
      attack.participants, flood.ids, flood.robot, flood.heavy_tiles, flood.rate_hz,
      flood.distinct_keys, std::chrono::duration<double>(attack.start).count(),
      std::chrono::duration<double>(attack.stop).count(), kRecoverySeconds);
  std::cout << "| robots | latency p50 / p99, quiet run | p50 / p99, during the flood | "
               "p50 / p99, after | server MB: quiet run peak / flooded run peak / at the end | "
               "flood tiles sent | the server's tile refusals |\n"
               "|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& row = rows[i];
    if (!row.attacked || !row.attacked->flood_started_s) continue;
    const FleetRunResult& attacked = *row.attacked;
    const double started = *attacked.flood_started_s;
    const double stopped = attacked.flood_stopped_s.value_or(attacked.seconds);
    const std::vector<double> during = LatenciesBetween(attacked, started, stopped);
    const std::vector<double> after =
        LatenciesBetween(attacked, stopped + kRecoverySeconds, attacked.seconds);
    const std::string refusals = TileRefusals(attacked.server_output);
    const int64_t end_rss = attacked.server_rss.empty() ? 0 : attacked.server_rss.back().second;
    const auto p = [](const std::vector<double>& values, double q) {
      return Percentile(values, q);
    };
    std::cout << fmt::format(
        "| {} | {} / {} | {} / {} | {} / {} | {:.0f} / {:.0f} / {:.0f} | {} | {} |\n", row.robots,
        Fmt(p(row.tiles.latencies_ms, 50), " ms"), Fmt(p(row.tiles.latencies_ms, 99), ""),
        Fmt(p(during, 50), " ms"), Fmt(p(during, 99), ""), Fmt(p(after, 50), " ms"),
        Fmt(p(after, 99), ""), row.tiles.server_peak_rss_bytes / 1e6,
        attacked.server_peak_rss_bytes / 1e6, end_rss / 1e6, attacked.hostile_tiles_written,
        refusals);
    (*json)[i]["hostile"] = {
        {"participants", attack.participants},
        {"ids_per_participant", flood.ids},
        {"flood_s", {started, stopped}},
        {"latency_ms_during",
         {{"p50", p(during, 50).value_or(-1)},
          {"p99", p(during, 99).value_or(-1)},
          {"updates", during.size()},
          {"latest", LatestBetween(attacked, started, stopped, 8)}}},
        {"latency_ms_after",
         {{"p50", p(after, 50).value_or(-1)}, {"p99", p(after, 99).value_or(-1)}}},
        {"server_peak_rss_bytes", attacked.server_peak_rss_bytes},
        {"server_rss_bytes_at_end", end_rss},
        {"flood_tiles_sent", attacked.hostile_tiles_written},
        {"server_tile_refusals", refusals}};
  }
}

// The attack of --hostile: the flood runs through the middle third of the run, so that the run
// shows the honest robots before, during and after it.
HostileAttack Attack(const BenchFleetArgs& args) {
  HostileAttack attack;
  attack.participants = args.hostile_participants;
  attack.flood.ids = args.hostile_ids;
  const auto duration = std::chrono::milliseconds(
      static_cast<int64_t>(std::llround(args.scenario.duration_s * 1000.0)));
  attack.start = duration / 3;
  attack.stop = 2 * duration / 3;
  return attack;
}

uint64_t Updates(const FleetRunResult& run) {
  uint64_t updates = 0;
  for (const auto& [name, robot] : run.robots) updates += robot.updates;
  return updates;
}

int RunBenchFleet(const BenchFleetArgs& args) {
  const FleetScenarioArgs& scenario = args.scenario;
  const auto kind = sim::TerrainKindFromName(scenario.terrain);
  if (!kind) {
    std::cerr << "fleetmap bench fleet: --terrain \"" << scenario.terrain
              << "\" is not a terrain kind\n";
    return cli::kExitBadInput;
  }
  FleetSimOptions base = ScenarioFleetOptions(*kind, scenario);
  for (const int robots : args.robots) {
    base.robots = robots;
    if (const Status valid = base.Validate(); !valid.ok()) {
      std::cerr << "fleetmap bench fleet: " << valid.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  base.security_dir = args.security_dir;
  grid::OccupancyGrid truth;
  if (const int code = PrepareFleetRuns("fleetmap bench fleet", &base, &truth);
      code != cli::kExitOk) {
    return code;
  }

  std::vector<Row> rows;
  for (const int robots : args.robots) {
    Row row;
    row.robots = robots;
    std::vector<std::string> wires = {"tiles"};
    if (args.compare_wire != "none") wires.push_back(args.compare_wire);
    for (const std::string& wire : wires) {
      FleetSimOptions options = base;
      options.robots = robots;
      options.wire = wire;
      options.measure_baselines = wire == "tiles";
      ProgressLine progress = ProgressLine::OnStderr();
      StatusOr<FleetRunResult> run = RunFleet(options, [&](double seconds) {
        progress.Update(
            seconds < 0
                ? fmt::format("{} robots, {} wire: the agents finish measuring the grid wires",
                              robots, wire)
                : fmt::format("{} robots, {} wire: {:.0f} / {:.0f} s", robots, wire, seconds,
                              scenario.duration_s));
      });
      progress.Finish();
      if (!run.ok()) {
        std::cerr << "fleetmap bench fleet: " << run.status().message() << "\n";
        return 1;
      }
      if (wire == "tiles") {
        row.tiles = std::move(run).value();
      } else {
        row.compared = std::move(run).value();
      }
    }
    if (args.hostile) {
      FleetSimOptions options = base;
      options.robots = robots;
      options.hostile = Attack(args);
      ProgressLine progress = ProgressLine::OnStderr();
      StatusOr<FleetRunResult> run = RunFleet(options, [&](double seconds) {
        progress.Update(fmt::format("{} robots, tiles wire, hostile flood: {:.0f} / {:.0f} s",
                                    robots, seconds, scenario.duration_s));
      });
      progress.Finish();
      if (!run.ok()) {
        std::cerr << "fleetmap bench fleet: " << run.status().message() << "\n";
        return 1;
      }
      row.attacked = std::move(run).value();
    }
    auto quality = metrics::CompareMaps(ResampleOnto(row.tiles.fused, truth), truth);
    if (quality.ok()) row.quality = *quality;
    rows.push_back(std::move(row));
  }

  std::cout << fmt::format(
      "fleet benchmark: {} {} m, seed {}, {:.0f} s per run, {} scans/s per robot\n\n",
      scenario.terrain, scenario.size, scenario.seed, scenario.duration_s, scenario.rate);
  std::cout << "Bytes: the vector tiles' payload bytes, and what the same map changes would have "
               "cost on each ROS-native grid wire as the agents measured them (payload bytes of "
               "the samples; in brackets, how many times the tiles' bytes).\n\n";
  std::cout << "| robots | tile bytes | map changes |";
  for (const BaselineBytes& baseline : Baselines({})) std::cout << " " << baseline.name << " |";
  std::cout << " tiles vs the smallest baseline |\n|---|---|---|---|---|---|---|---|---|\n";
  nlohmann::json json = nlohmann::json::array();
  for (const Row& row : rows) {
    std::cout << fmt::format("| {} | {} | {} |", row.robots, row.tiles.total_bytes,
                             row.tiles.baselines.events);
    nlohmann::json baselines;
    for (const BaselineBytes& baseline : Baselines(row.tiles.baselines)) {
      std::cout << " " << BytesAndRatio(baseline.bytes, row.tiles.total_bytes) << " |";
      baselines[baseline.key] = baseline.bytes;
    }
    std::cout << " " << HeadlineRatio(row.tiles.total_bytes, row.tiles.baselines) << " |\n";
    json.push_back({{"robots", row.robots},
                    {"tile_bytes", row.tiles.total_bytes},
                    {"map_changes", row.tiles.baselines.events},
                    {"baselines", baselines},
                    {"smallest_baseline", SmallestBaseline(row.tiles.baselines).key},
                    {"baselines_pending_patches", row.tiles.baselines.patches_pending}});
  }

  if (args.compare_wire != "none") {
    std::cout << fmt::format(
        "\nThe same scenario with `--wire {}` agents, for real (its own map changes, which "
        "differ from the tile run's with timing):\n\n"
        "| robots | {} bytes | whole grids | patches | vs the tile run's bytes |\n"
        "|---|---|---|---|---|\n",
        args.compare_wire, args.compare_wire);
    for (size_t i = 0; i < rows.size(); ++i) {
      const Row& row = rows[i];
      if (!row.compared) continue;
      uint64_t whole = 0, updates = 0;
      for (const auto& [name, robot] : row.compared->robots) {
        whole += robot.whole_grids;
        updates += robot.updates;
      }
      std::cout << fmt::format("| {} | {} | {} | {} | {} |\n", row.robots,
                               row.compared->total_bytes, whole, updates - whole,
                               BytesAndRatio(row.compared->total_bytes, row.tiles.total_bytes));
      json[i]["compared_run"] = {{"wire", args.compare_wire},
                                 {"total_bytes", row.compared->total_bytes},
                                 {"whole_grids", whole},
                                 {"patches", updates - whole}};
    }
  }

  std::cout << "\nThe tile wire:\n\n| robots | tile updates | bytes/update | latency p50 / p95 / "
               "p99 | server CPU | server MB | MS / OPDF / UPDF |\n"
               "|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& row = rows[i];
    const uint64_t updates = Updates(row.tiles);
    const auto p50 = Percentile(row.tiles.latencies_ms, 50);
    const auto p95 = Percentile(row.tiles.latencies_ms, 95);
    const auto p99 = Percentile(row.tiles.latencies_ms, 99);
    const double cpu = 100.0 * row.tiles.server_cpu_seconds / std::max(1e-9, row.tiles.seconds);
    std::cout << fmt::format(
        "| {} | {} | {:.0f} | {} / {} / {} | {:.0f} % | {:.0f} | {} / {} / {} |\n", row.robots,
        updates, updates > 0 ? static_cast<double>(row.tiles.total_bytes) / updates : 0.0,
        Fmt(p50, " ms"), Fmt(p95, ""), Fmt(p99, ""), cpu, row.tiles.server_peak_rss_bytes / 1e6,
        Fmt(row.quality.map_score, ""), Fmt(row.quality.occupied_picture_distance, ""),
        Fmt(row.quality.unoccupied_picture_distance, ""));
    json[i]["tile_updates"] = updates;
    json[i]["latency_ms"] = {{"p50", p50.value_or(-1)},
                             {"p95", p95.value_or(-1)},
                             {"p99", p99.value_or(-1)},
                             {"latest", LatestBetween(row.tiles, 0.0, row.tiles.seconds, 12)}};
    json[i]["server_cpu_percent"] = cpu;
    json[i]["server_peak_rss_bytes"] = row.tiles.server_peak_rss_bytes;
    json[i]["ms"] = row.quality.map_score.value_or(-1);
    json[i]["opdf"] = row.quality.occupied_picture_distance.value_or(-1);
    json[i]["updf"] = row.quality.unoccupied_picture_distance.value_or(-1);
  }
  if (args.hostile) PrintHostileTable(rows, Attack(args), &json);
  if (args.single_robot && !rows.empty()) {
    const Row& fleet = rows.back();
    FleetSimOptions options = base;
    options.robots = 1;
    options.wire = "tiles";
    options.duration = base.duration * fleet.robots;
    ProgressLine progress = ProgressLine::OnStderr();
    StatusOr<FleetRunResult> single = RunFleet(options, [&](double seconds) {
      progress.Update(fmt::format("1 robot for {:.0f} s: {:.0f} s",
                                  std::chrono::duration<double>(options.duration).count(),
                                  seconds));
    });
    progress.Finish();
    if (!single.ok()) {
      std::cerr << "fleetmap bench fleet: " << single.status().message() << "\n";
      return 1;
    }
    const auto alone = metrics::CompareMaps(ResampleOnto(single->fused, truth), truth);
    if (alone.ok()) {
      std::cout << fmt::format(
          "\nOne robot for {:.0f} s against {} robots for {:.0f} s, fused map vs ground truth: "
          "MS {} vs {}, OPDF {} vs {}, UPDF {} vs {}\n",
          std::chrono::duration<double>(options.duration).count(), fleet.robots,
          scenario.duration_s, Fmt(alone->map_score, ""), Fmt(fleet.quality.map_score, ""),
          Fmt(alone->occupied_picture_distance, ""),
          Fmt(fleet.quality.occupied_picture_distance, ""),
          Fmt(alone->unoccupied_picture_distance, ""),
          Fmt(fleet.quality.unoccupied_picture_distance, ""));
    }
  }
  if (!args.json_path.empty()) {
    if (const Status written = WriteFileAtomically(args.json_path, json.dump(2) + "\n");
        !written.ok()) {
      std::cerr << "fleetmap bench fleet: " << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  return cli::kExitOk;
}

}  // namespace

void AddBenchFleetCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchFleetArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "fleet",
      "Simulated fleets of growing size, the tile wire against the grid wires: a scaling table");
  command->add_option("--robots", args->robots, "fleet sizes, e.g. 1 4 16");
  AddFleetScenarioOptions(command, &args->scenario);
  command->add_option("--json", args->json_path, "write the rows as JSON");
  command
      ->add_option("--compare-wire", args->compare_wire,
                   "also run each fleet on this grid wire for real: grid, grid-updates, "
                   "grid-updates-zstd, or none")
      ->check(CLI::IsMember({"grid", "grid-updates", "grid-updates-zstd", "none"}))
      ->capture_default_str();
  command->add_flag("--single-robot", args->single_robot,
                    "also one robot for (largest fleet x duration), to compare map quality");
  command->add_flag("--hostile", args->hostile,
                    "also run each fleet while hostile peers flood the server through the middle "
                    "third of the run, and compare");
  command
      ->add_option("--hostile-participants", args->hostile_participants,
                   "hostile DDS participants (--hostile)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command
      ->add_option("--hostile-ids", args->hostile_ids,
                   "robot ids each hostile participant claims (--hostile)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--security", args->security_dir,
                      "run every fleet with DDS Security from this folder (fleetmap security: "
                      "identities server, robot0.. robot<N-1> and the viewer observer)");
  command->callback([args, exit_code] { *exit_code = RunBenchFleet(*args); });
}

}  // namespace fleetmap::bench
