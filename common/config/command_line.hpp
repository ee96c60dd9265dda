#pragma once

// The command-line parse every program of the house shares (fleetmap-server, fleetmap-agent and
// `fleetmap` with all its subcommands), so that all of them behave alike:
// - `--help` prints the help and exits 0;
// - `--version` prints VersionText (version.hpp) and exits 0;
// - every option CLI11 refuses (unknown flag, bad or missing value, a check that fails) prints one
//   line naming the command and the option, and exits 2, the exit code of bad input everywhere
//   (cli/inputs/exit_codes.hpp). CLI11 would exit with its own codes (105, 106, 109...), and its
//   PositiveNumber / NonNegativeNumber checks would print the largest double in full; they say
//   "must be > 0, got -3" instead.

#include <CLI/CLI.hpp>

#include <optional>

namespace fleetmap::config {

inline constexpr int kExitBadCommandLine = 2;

// Adds --version to `app`, then parses. Returns the code to exit with when the program should
// not run: 0 after --help or --version, kExitBadCommandLine after a refused option; nullopt to go
// on. argv[0] names the program in the messages.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv);

}  // namespace fleetmap::config
