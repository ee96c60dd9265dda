#pragma once

// `fleetmap bench flood`: hostile DDS participants that flood a running fleet's server with
// well-formed tiles (HostileFlood), until Ctrl-C / SIGTERM or --duration. A process of its own,
// so that what it costs (building, serializing and sending tens of thousands of tiles) is not
// charged to whoever measures the fleet: `bench fleet --hostile` starts it for the middle third
// of a run. Also a load to point at one's own fleet. Prints one line when it floods and one with
// the tiles written when it stops.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace fleetmap::bench {

void AddBenchFloodCommand(CLI::App& app, int* exit_code);

// The tiles a finished `bench flood` says it wrote, from its output (0 if it did not say).
uint64_t TilesWrittenByFlood(const std::string& output);

}  // namespace fleetmap::bench
