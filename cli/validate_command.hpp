#pragma once

// `fleetmap validate MAP.yaml IN.vmap [--json]`: checks a .vmap against the grid it was made
// from, exactly (vector_map::Validator): the epsilon-error constraint (every delimitation point
// within epsilon of an edge) and continuity (every point of every edge within epsilon of a
// delimitation point). Exit code 0 when both hold, 1 when either is violated, 2 on bad input.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"

namespace fleetmap::cli {

inline constexpr int kExitConstraintViolated = 1;

struct ValidateCommandOptions {
  std::string map_yaml;
  std::string vmap;
  bool json = false;
  int64_t max_cells = kDefaultMaxCells;
};

int RunValidate(const ValidateCommandOptions& options, std::ostream& out, std::ostream& err);

void AddValidateCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
