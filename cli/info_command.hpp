#pragma once

// `fleetmap info MAP.yaml [--json]`: what a map_server map holds (size, resolution, origin,
// bounds, cell states) and how it was read (mode, negate, thresholds).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

namespace fleetmap::cli {

struct InfoOptions {
  std::string map_yaml;
  bool json = false;
  bool allow_outside_dir = false;
  int64_t max_cells = 400'000'000;
};

// Loads the map and prints its summary to `out` (text, or one JSON object with --json). On a bad
// input prints "<file>: <problem>" to `err` and returns kExitBadInput; kExitOk otherwise.
int RunInfo(const InfoOptions& options, std::ostream& out, std::ostream& err);

// Registers the `info` subcommand on `app`; when it runs, its exit code goes to `*exit_code`.
void AddInfoCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
