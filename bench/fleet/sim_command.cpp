#include "bench/fleet/sim_command.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "bench/fleet/fleet_scenario.hpp"
#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/fleet_sim_report.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

struct SimArgs {
  int robots = FleetSimOptions{}.robots;
  FleetScenarioArgs scenario{.size = FleetSimOptions{}.size,
                             .seed = FleetSimOptions{}.seed,
                             .rate = FleetSimOptions{}.scans_per_second};
  std::string out_dir = "out/sim";
  bool compare = true;
  std::string compare_wire = "grid-updates-zstd";
};

int RunSim(const SimArgs& args) {
  const auto kind = sim::TerrainKindFromName(args.scenario.terrain);
  if (!kind) {
    std::cerr << "fleetmap sim: --terrain \"" << args.scenario.terrain
              << "\" is not a terrain kind (office, maze, unstructured)\n";
    return cli::kExitBadInput;
  }
  FleetSimOptions fleet = ScenarioFleetOptions(*kind, args.scenario);
  fleet.robots = args.robots;
  if (const Status valid = fleet.Validate(); !valid.ok()) {
    std::cerr << "fleetmap sim: " << valid.message() << "\n";
    return cli::kExitBadInput;
  }
  // The ground truth the report scores against: the same seeded terrain the agents explore.
  grid::OccupancyGrid truth;
  if (const int code = PrepareFleetRuns("fleetmap sim", &fleet, &truth); code != cli::kExitOk) {
    return code;
  }

  const auto run = [&](const std::string& wire) -> StatusOr<FleetRunResult> {
    FleetSimOptions options = fleet;
    options.wire = wire;
    options.measure_baselines = wire == "tiles";
    return RunFleet(options, [&](double seconds) {
      if (seconds < 0) {
        std::cerr << fmt::format("\r[{} wire] the agents finish measuring the grid wires", wire)
                  << std::flush;
        return;
      }
      std::cerr << fmt::format("\r[{} wire] {:.0f} / {:.0f} s", wire, seconds,
                               args.scenario.duration_s)
                << std::flush;
    });
  };
  StatusOr<FleetRunResult> tiles = run("tiles");
  std::cerr << "\n";
  if (!tiles.ok()) {
    std::cerr << "fleetmap sim: " << tiles.status().message() << "\n";
    return 1;
  }
  std::optional<FleetRunResult> compared;
  if (args.compare) {
    StatusOr<FleetRunResult> compared_run = run(args.compare_wire);
    std::cerr << "\n";
    if (!compared_run.ok()) {
      std::cerr << "fleetmap sim: the " << args.compare_wire
                << " run failed: " << compared_run.status().message() << "\n";
      return 1;
    }
    compared = std::move(compared_run).value();
  }
  StatusOr<std::string> summary = WriteFleetReport(fleet, *tiles, compared, truth, args.out_dir);
  if (!summary.ok()) {
    std::cerr << "fleetmap sim: " << summary.status().message() << "\n";
    return 1;
  }
  std::cout << *summary << "\n";
  return cli::kExitOk;
}

}  // namespace

void AddSimCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* command = app.add_subcommand(
      "sim", "Run a simulated fleet (server + N agent processes over DDS on loopback) and report");
  command->add_option("--robots", args->robots, "robots (1..64)");
  AddFleetScenarioOptions(command, &args->scenario);
  command->add_option("--out", args->out_dir, "report folder");
  command->add_flag("!--no-compare", args->compare,
                    "skip the same run on a grid wire (--compare-wire) for real");
  command
      ->add_option("--compare-wire", args->compare_wire,
                   "the grid wire of the second run: grid, grid-updates or grid-updates-zstd")
      ->check(CLI::IsMember({"grid", "grid-updates", "grid-updates-zstd"}))
      ->capture_default_str();
  command->callback([args, exit_code] { *exit_code = RunSim(*args); });
}

}  // namespace fleetmap::bench
