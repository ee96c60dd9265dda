#include "bench/fleet/fleet_scenario.hpp"

#include <chrono>
#include <iostream>
#include <utility>

#include "cli/inputs/exit_codes.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::bench {

void AddFleetScenarioOptions(CLI::App* command, FleetScenarioArgs* args) {
  command->add_option("--terrain", args->terrain, "office, maze, unstructured or warehouse");
  command->add_option("--size", args->size, "terrain side, metres");
  command->add_option("--seed", args->seed, "terrain seed");
  command->add_option("--duration", args->duration_s, "seconds per run");
  command->add_option("--rate", args->rate, "laser scans per second per robot");
}

FleetSimOptions ScenarioFleetOptions(sim::TerrainKind kind, const FleetScenarioArgs& args) {
  FleetSimOptions options;
  options.kind = kind;
  options.size = args.size;
  options.seed = args.seed;
  options.scans_per_second = args.rate;
  options.duration = std::chrono::milliseconds(static_cast<int64_t>(args.duration_s * 1000));
  return options;
}

int PrepareFleetRuns(const std::string& command, FleetSimOptions* base,
                     grid::OccupancyGrid* truth) {
  StatusOr<std::string> binaries = FindFleetBinaries();
  if (!binaries.ok()) {
    std::cerr << command << ": " << binaries.status().message() << "\n";
    return 1;
  }
  base->bin_dir = *binaries;
  auto generator =
      sim::TerrainGenerator::Create({.kind = base->kind, .size = base->size, .seed = base->seed});
  if (!generator.ok()) {
    std::cerr << command << ": " << generator.status().message() << "\n";
    return cli::kExitBadInput;
  }
  StatusOr<grid::OccupancyGrid> rasterized = sim::RasterizeTerrain(generator->Generate(), 0.05);
  if (!rasterized.ok()) {
    std::cerr << command << ": " << rasterized.status().message() << "\n";
    return 1;
  }
  *truth = std::move(rasterized).value();
  return cli::kExitOk;
}

}  // namespace fleetmap::bench
