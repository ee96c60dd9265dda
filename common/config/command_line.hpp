#pragma once

// The command-line parse every program of the house shares (fleetmap-server, fleetmap-agent and
// `fleetmap` with all its subcommands), so that all of them behave alike:
// - `--help` prints the help and exits 0;
// - `--version` prints VersionText (version.hpp) and exits 0;
// - every option CLI11 refuses (unknown flag, bad or missing value, a check that fails) prints one
//   line naming the command and the option, and exits 2, the exit code of bad input everywhere
//   (cli/inputs/exit_codes.hpp). CLI11 would exit with its own codes (105, 106, 109...), and its
//   PositiveNumber / NonNegativeNumber checks would print the largest double in full; they say
//   "must be > 0, got -3" instead;
// - the commands given as ConfigurableCommand also take their options from a config file and the
//   environment (configurable_command.hpp).

#include <CLI/CLI.hpp>

#include <optional>
#include <vector>

#include "common/config/configurable_command.hpp"

namespace fleetmap::config {

inline constexpr int kExitBadCommandLine = 2;

// Adds --version to `app`, then parses, with the config file's and the environment's settings of
// each of `configurable` the command line selects. Returns the code to exit with when the program
// should not run: 0 after --help or --version, kExitBadCommandLine after a refused option or
// setting; nullopt to go on. argv[0] names the program in the messages.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::vector<ConfigurableCommand*>& configurable = {});

// ParseCommandLine for a fleet program whose App is its whole command line (fleetmap-server,
// fleetmap-agent): its options also come from --config (ROS 2 node name `ros_node`) and the DDS
// environment (DdsEnvironment), and --print-config prints them and exits 0.
std::optional<int> ParseFleetProgram(CLI::App& app, int argc, char** argv,
                                     const std::string& ros_node);

}  // namespace fleetmap::config
