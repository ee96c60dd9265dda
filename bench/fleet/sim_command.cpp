#include "bench/fleet/sim_command.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/exit_codes.hpp"
#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/fleet_sim_report.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::cli {
namespace {

struct SimArgs {
  FleetSimOptions fleet;
  std::string terrain = "office";
  double duration_s = 60.0;
  std::string out_dir = "out/sim";
  bool compare = true;
};

int RunSim(SimArgs& args) {
  const auto kind = sim::TerrainKindFromName(args.terrain);
  if (!kind) {
    std::cerr << "fleetmap sim: --terrain \"" << args.terrain
              << "\" is not a terrain kind (office, maze, unstructured)\n";
    return kExitBadInput;
  }
  args.fleet.kind = *kind;
  args.fleet.duration = std::chrono::milliseconds(static_cast<int64_t>(args.duration_s * 1000));
  if (const Status valid = args.fleet.Validate(); !valid.ok()) {
    std::cerr << "fleetmap sim: " << valid.message() << "\n";
    return kExitBadInput;
  }
  StatusOr<std::string> binaries = FindFleetBinaries();
  if (!binaries.ok()) {
    std::cerr << "fleetmap sim: " << binaries.status().message() << "\n";
    return 1;
  }
  args.fleet.bin_dir = *binaries;

  // The ground truth the report scores against: the same seeded terrain the agents explore.
  sim::TerrainOptions terrain_options{
      .kind = *kind, .size = args.fleet.size, .seed = args.fleet.seed};
  auto generator = sim::TerrainGenerator::Create(terrain_options);
  if (!generator.ok()) {
    std::cerr << "fleetmap sim: " << generator.status().message() << "\n";
    return kExitBadInput;
  }
  auto truth = sim::RasterizeTerrain(generator->Generate(), 0.05);
  if (!truth.ok()) {
    std::cerr << "fleetmap sim: " << truth.status().message() << "\n";
    return 1;
  }

  const auto run = [&](const std::string& wire) -> StatusOr<FleetRunResult> {
    FleetSimOptions options = args.fleet;
    options.wire = wire;
    return RunFleet(options, [&](double seconds) {
      std::cerr << fmt::format("\r[{} wire] {:.0f} / {:.0f} s", wire, seconds, args.duration_s)
                << std::flush;
    });
  };
  StatusOr<FleetRunResult> tiles = run("tiles");
  std::cerr << "\n";
  if (!tiles.ok()) {
    std::cerr << "fleetmap sim: " << tiles.status().message() << "\n";
    return 1;
  }
  std::optional<FleetRunResult> grid;
  if (args.compare) {
    StatusOr<FleetRunResult> grid_run = run("grid");
    std::cerr << "\n";
    if (!grid_run.ok()) {
      std::cerr << "fleetmap sim: the grid-wire run failed: " << grid_run.status().message()
                << "\n";
      return 1;
    }
    grid = std::move(grid_run).value();
  }
  StatusOr<std::string> summary = WriteFleetReport(args.fleet, *tiles, grid, *truth, args.out_dir);
  if (!summary.ok()) {
    std::cerr << "fleetmap sim: " << summary.status().message() << "\n";
    return 1;
  }
  std::cout << *summary << "\n";
  return kExitOk;
}

}  // namespace

void AddSimCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* command = app.add_subcommand(
      "sim", "Run a simulated fleet (server + N agent processes over DDS on loopback) and report");
  command->add_option("--robots", args->fleet.robots, "robots (1..64)");
  command->add_option("--terrain", args->terrain, "office, maze or unstructured");
  command->add_option("--size", args->fleet.size, "terrain side, metres");
  command->add_option("--seed", args->fleet.seed, "terrain seed");
  command->add_option("--duration", args->duration_s, "seconds per run");
  command->add_option("--rate", args->fleet.scans_per_second, "laser scans per second per robot");
  command->add_option("--out", args->out_dir, "report folder");
  command->add_flag("!--no-compare", args->compare, "skip the same run on the grid wire");
  command->callback([args, exit_code] { *exit_code = RunSim(*args); });
}

}  // namespace fleetmap::cli
