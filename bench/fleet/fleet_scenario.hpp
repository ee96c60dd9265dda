#pragma once

// What the fleet commands (`fleetmap sim`, `bench fleet`, `bench loss`) share: the flags of the
// scenario a fleet runs in, and the steps between parsing them and the first run.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "bench/fleet/fleet_sim.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {

// The defaults differ by command; each sets its own.
struct FleetScenarioArgs {
  std::string terrain = "office";
  double size = 40.0;  // metres
  uint32_t seed = 1;
  double duration_s = 60.0;
  double rate = 10.0;  // laser scans per second per robot
};

// Registers --terrain, --size, --seed, --duration and --rate on `command`, in that order.
void AddFleetScenarioOptions(CLI::App* command, FleetScenarioArgs* args);

// The fleet options of the scenario: terrain, size, seed, scan rate and duration; the rest default.
FleetSimOptions ScenarioFleetOptions(sim::TerrainKind kind, const FleetScenarioArgs& args);

// Finds the fleet binaries (into base->bin_dir) and rasterizes the ground truth of the scenario's
// terrain at 5 cm (into *truth). On failure prints "<command>: <why>" on stderr and returns the
// exit code (kExitBadInput for a terrain the generator refuses, 1 otherwise); kExitOk on success.
int PrepareFleetRuns(const std::string& command, FleetSimOptions* base, grid::OccupancyGrid* truth);

}  // namespace fleetmap::bench
