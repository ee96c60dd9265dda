#pragma once

// `fleetmap register A.yaml B.yaml [--json] [--min-confidence P]`: the rigid transform a_from_b
// that takes map B's frame into map A's (common/registration), with its confidence and overlap;
// "found" is the server's placement decision (the same bar), and the best guess is printed
// whether found or not.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "common/registration/registration.hpp"

namespace fleetmap::cli {

struct RegisterOptions {
  std::string map_a_yaml;
  std::string map_b_yaml;
  bool json = false;
  int64_t max_cells = 400'000'000;
  // The placement bar: found only at this confidence or above (the server's by default).
  double min_confidence = registration::kPlacementConfidence;
  // The drift-tolerant verification's bound (docs/registration.md, Drift); 0, rigid, as the
  // server's default.
  double max_drift_per_m = registration::RegistrationOptions{}.max_drift_per_m;
};

// Loads both maps and registers B to A; prints the result to `out` (text, or one JSON line with
// --json). Returns kExitOk whether a transform was found or not; kExitBadInput, with the file
// and the problem on `err`, when a map cannot be read or the pair cannot be registered, or the
// option named when min_confidence is outside [0, 1].
int RunRegister(const RegisterOptions& options, std::ostream& out, std::ostream& err);

// Registers the `register` subcommand on `app`; when it runs, its exit code goes to `*exit_code`.
void AddRegisterCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
