#pragma once

// `fleetmap compare A.yaml B.yaml [--json] [--window N]`: the map-quality metrics of ALGORITHMS.md
// 1.1 (MS, CC, PC, OPDF, UPDF) of A (robot map) against B (ground truth). Both maps must have the
// same size, resolution and origin. A metric whose denominator is zero prints `undefined` (JSON
// null).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"

namespace fleetmap::cli {

struct CompareCommandOptions {
  std::string robot_yaml;
  std::string truth_yaml;
  bool json = false;
  int window = 20;  // OPDF / UPDF search window, cells (square)
  int64_t max_cells = kDefaultMaxCells;
};

int RunCompare(const CompareCommandOptions& options, std::ostream& out, std::ostream& err);

void AddCompareCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
