#pragma once

// `fleetmap bench quarantine`: what one robot can do to the fleet map (issue 30). A server and a
// robot that established a building's walls, then one offender per scenario, all real processes
// over DDS on loopback: a fresh id painting free space, an honest robot given a transform 2 m
// off, one whose map is turned 10 degrees, and a real change (shelf rows taken away) seen by one
// robot and confirmed by a second. Reports the established wall cells erased (the most at any
// moment), the time from the offender's first tile to its quarantine, and the time from the
// confirming robot's first tile to the change in the fused map; CSV and JSON beside the table.

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

void AddBenchQuarantineCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
