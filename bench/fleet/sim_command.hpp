#pragma once

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

// `fleetmap sim`: a simulated fleet over DDS (server + N agent processes) and its report.
void AddSimCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
