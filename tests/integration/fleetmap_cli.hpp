#pragma once

// Runs the real `fleetmap` binary of this build, for the CLI integration tests.

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/scratch_dir.hpp"  // ReadFile

namespace fleetmap::testing {

inline process::CommandResult RunFleetmap(
    const std::vector<std::string>& args,
    std::chrono::milliseconds timeout = std::chrono::seconds(120)) {
  std::vector<std::string> argv = {std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap"};
  argv.insert(argv.end(), args.begin(), args.end());
  return process::RunCommand(std::move(argv), timeout);
}

// A fresh, empty directory for one test's outputs, unique to this process: <tmp>/<prefix>_<pid>.
inline std::string FreshTempDir(const std::string& prefix) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(getpid()))).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace fleetmap::testing
