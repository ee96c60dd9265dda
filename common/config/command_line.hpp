#pragma once

// One exit code for bad input on every program of the house: 2 (cli/inputs/exit_codes.hpp), also
// for an option CLI11 refuses (it would exit with its own codes, 105, 106 and so on).

#include <CLI/CLI.hpp>

#include <optional>

namespace fleetmap::config {

inline constexpr int kExitBadCommandLine = 2;

// Parses the command line. Returns the code to exit with when the program should not run: 0
// after --help, 2 after CLI11's message for a refused option; nullopt to go on.
inline std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : kExitBadCommandLine;
  }
  return std::nullopt;
}

}  // namespace fleetmap::config
