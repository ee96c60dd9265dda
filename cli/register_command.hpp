#pragma once

// `fleetmap register A.yaml B.yaml [--json]`: the rigid transform a_from_b that takes map B's
// frame into map A's (common/registration), with its confidence and overlap, or why none was
// found.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

namespace fleetmap::cli {

struct RegisterOptions {
  std::string map_a_yaml;
  std::string map_b_yaml;
  bool json = false;
  int64_t max_cells = 400'000'000;
};

// Loads both maps and registers B to A; prints the result to `out` (text, or one JSON line with
// --json). Returns kExitOk whether a transform was found or not; kExitBadInput, with the file
// and the problem on `err`, when a map cannot be read or the pair cannot be registered.
int RunRegister(const RegisterOptions& options, std::ostream& out, std::ostream& err);

// Registers the `register` subcommand on `app`; when it runs, its exit code goes to `*exit_code`.
void AddRegisterCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
