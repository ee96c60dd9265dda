#pragma once

// Exit codes shared by every `fleetmap` subcommand. Usage errors (unknown flag, missing or bad
// value) exit kExitBadInput too, and --help and --version exit 0 (common/config/command_line.hpp).

namespace fleetmap::cli {

inline constexpr int kExitOk = 0;
// The input is bad or missing (unreadable map, malformed YAML, image too large...): the message on
// stderr names the file and the problem.
inline constexpr int kExitBadInput = 2;

}  // namespace fleetmap::cli
