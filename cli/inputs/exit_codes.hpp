#pragma once

// Exit codes shared by every `fleetmap` subcommand. Usage errors (unknown flag, missing argument)
// exit with CLI11's own non-zero codes; --help exits 0.

namespace fleetmap::cli {

inline constexpr int kExitOk = 0;
// The input is bad or missing (unreadable map, malformed YAML, image too large...): the message on
// stderr names the file and the problem.
inline constexpr int kExitBadInput = 2;

}  // namespace fleetmap::cli
