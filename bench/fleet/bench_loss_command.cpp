#include "bench/fleet/bench_loss_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/fleet/fleet_scenario.hpp"
#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/fleet_sim_report.hpp"
#include "bench/report/bench_command.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/metrics/map_quality.hpp"
#include "common/process/lossy_network_namespace.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

struct BenchLossArgs {
  std::vector<int> loss_percents = {0, 5, 20, 40};
  int robots = 4;
  FleetScenarioArgs scenario{.size = 40.0, .duration_s = 40.0};
  std::string json_path;
  std::string csv_path;
};

struct Row {
  int loss_percent = 0;
  FleetRunResult run;
  std::optional<double> p50, p95, p99, max;
  metrics::QualityScores quality;
};

std::string Ms(const std::optional<double>& value) {
  return value ? fmt::format("{:.0f}", *value) : std::string("n/a");
}

std::string MachineDescription() {
  std::string cpu = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return fmt::format("{}, {} cores online", cpu, sysconf(_SC_NPROCESSORS_ONLN));
}

int RunBenchLoss(const BenchLossArgs& args) {
  for (const int loss : args.loss_percents) {
    if (loss < 0 || loss > 90) {
      std::cerr << "fleetmap bench loss: --loss " << loss << " is outside 0..90 %\n";
      return cli::kExitBadInput;
    }
  }
  const FleetScenarioArgs& scenario = args.scenario;
  const auto kind = sim::TerrainKindFromName(scenario.terrain);
  if (!kind) {
    std::cerr << "fleetmap bench loss: --terrain \"" << scenario.terrain
              << "\" is not a terrain kind\n";
    return cli::kExitBadInput;
  }
  FleetSimOptions base = ScenarioFleetOptions(*kind, scenario);
  base.robots = args.robots;
  base.wire = "tiles";
  if (const Status valid = base.Validate(); !valid.ok()) {
    std::cerr << "fleetmap bench loss: " << valid.message() << "\n";
    return cli::kExitBadInput;
  }
  if (const Status available = process::LossyNetworkNamespace::CheckAvailable(); !available.ok()) {
    std::cerr << "fleetmap bench loss: " << available.message() << "\n";
    return 1;
  }
  grid::OccupancyGrid truth;
  if (const int code = PrepareFleetRuns("fleetmap bench loss", &base, &truth);
      code != cli::kExitOk) {
    return code;
  }

  std::vector<Row> rows;
  for (const int loss : args.loss_percents) {
    auto network = process::LossyNetworkNamespace::Create(loss);
    if (!network.ok()) {
      std::cerr << "fleetmap bench loss: " << network.status().message() << "\n";
      return 1;
    }
    StatusOr<FleetRunResult> run = UnavailableError("not run");
    {
      // The observer's participant and every process RunFleet starts live in the namespace.
      auto inside = (*network)->Enter();
      if (!inside.ok()) {
        std::cerr << "fleetmap bench loss: " << inside.status().message() << "\n";
        return 1;
      }
      ProgressLine progress = ProgressLine::OnStderr();
      run = RunFleet(base, [&](double seconds) {
        progress.Update(
            fmt::format("{} % loss: {:.0f} / {:.0f} s", loss, seconds, scenario.duration_s));
      });
      progress.Finish();
    }
    if (!run.ok()) {
      std::cerr << "fleetmap bench loss: " << run.status().message() << "\n";
      return 1;
    }
    Row row;
    row.loss_percent = loss;
    row.run = std::move(run).value();
    row.p50 = Percentile(row.run.latencies_ms, 50);
    row.p95 = Percentile(row.run.latencies_ms, 95);
    row.p99 = Percentile(row.run.latencies_ms, 99);
    row.max = Percentile(row.run.latencies_ms, 100);
    auto quality = metrics::CompareMaps(ResampleOnto(row.run.fused, truth), truth);
    if (quality.ok()) row.quality = *quality;
    rows.push_back(std::move(row));
  }

  const std::string machine = MachineDescription();
  std::cout << fmt::format(
      "loss benchmark: {} robots, {} {} m, seed {}, {:.0f} s per run, {} scans/s per robot, UDP "
      "on loopback in a network namespace (nftables random drop)\nmachine: {}\n\n",
      args.robots, scenario.terrain, scenario.size, scenario.seed, scenario.duration_s,
      scenario.rate, machine);
  std::cout << "| UDP loss | tile updates | fused tiles received | latency p50 / p95 / p99 / max "
               "(ms) | robots falsely lost | MS |\n|---|---|---|---|---|---|\n";
  nlohmann::json json = nlohmann::json::array();
  std::string csv =
      "loss_percent,robots,tile_updates,fused_tiles,p50_ms,p95_ms,p99_ms,max_ms,"
      "robots_falsely_lost,ms\n";
  for (const Row& row : rows) {
    uint64_t updates = 0;
    for (const auto& [name, robot] : row.run.robots) updates += robot.updates;
    const double ms = row.quality.map_score.value_or(-1);
    std::cout << fmt::format("| {} % | {} | {} | {} / {} / {} / {} | {} | {:.3f} |\n",
                             row.loss_percent, updates, row.run.latencies_ms.size(), Ms(row.p50),
                             Ms(row.p95), Ms(row.p99), Ms(row.max), row.run.robots_reported_lost,
                             ms);
    json.push_back({{"loss_percent", row.loss_percent},
                    {"robots", args.robots},
                    {"tile_updates", updates},
                    {"fused_tiles", row.run.latencies_ms.size()},
                    {"latency_ms",
                     {{"p50", row.p50.value_or(-1)},
                      {"p95", row.p95.value_or(-1)},
                      {"p99", row.p99.value_or(-1)},
                      {"max", row.max.value_or(-1)}}},
                    {"robots_falsely_lost", row.run.robots_reported_lost},
                    {"ms", ms},
                    {"machine", machine}});
    csv += fmt::format("{},{},{},{},{:.1f},{:.1f},{:.1f},{:.1f},{},{:.4f}\n", row.loss_percent,
                       args.robots, updates, row.run.latencies_ms.size(), row.p50.value_or(-1),
                       row.p95.value_or(-1), row.p99.value_or(-1), row.max.value_or(-1),
                       row.run.robots_reported_lost, ms);
  }
  for (const auto& [path, text] :
       {std::pair{args.json_path, json.dump(2) + "\n"}, std::pair{args.csv_path, csv}}) {
    if (path.empty()) continue;
    if (const Status written = WriteFileAtomically(path, text); !written.ok()) {
      std::cerr << "fleetmap bench loss: " << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  return cli::kExitOk;
}

}  // namespace

void AddBenchLossCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchLossArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "loss", "A simulated fleet on lossy UDP (network namespace + nftables; needs root)");
  command->add_option("--loss", args->loss_percents, "UDP loss rates in percent, e.g. 0 5 20 40");
  command->add_option("--robots", args->robots, "robots in the fleet");
  AddFleetScenarioOptions(command, &args->scenario);
  command->add_option("--json", args->json_path, "write the rows as JSON");
  command->add_option("--csv", args->csv_path, "write the rows as CSV");
  command->callback([args, exit_code] { *exit_code = RunBenchLoss(*args); });
}

}  // namespace fleetmap::bench
