#pragma once

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

// `fleetmap bench fleet`: simulated fleets of growing size, on the tile wire and the grid wire,
// in one run; a scaling table of bytes, latency, fused-map quality and server cost.
void AddBenchFleetCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
