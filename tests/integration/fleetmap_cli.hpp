#pragma once

// Runs the real `fleetmap` binary of this build, for the CLI integration tests.

#include <chrono>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"

namespace fleetmap::testing {

inline process::CommandResult RunFleetmap(
    const std::vector<std::string>& args,
    std::chrono::milliseconds timeout = std::chrono::seconds(120)) {
  std::vector<std::string> argv = {std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap"};
  argv.insert(argv.end(), args.begin(), args.end());
  return process::RunCommand(std::move(argv), timeout);
}

}  // namespace fleetmap::testing
