#pragma once

// `fleetmap view [--port 8080] [--bind 127.0.0.1]`: the web view of a live fleet. Joins the
// fleet's DDS domain as a reader and serves one page at http://<bind>:<port>/ that shows the fused
// map, the robots, the sub-map graph and the learned objects as they change (docs/view.md).

#include <CLI/CLI.hpp>
#include <chrono>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "cli/fleet_reader_options.hpp"
#include "common/config/configurable_command.hpp"

namespace fleetmap::cli {

struct ViewOptions {
  int port = 8080;  // 0: any free port (printed)
  std::string bind = "127.0.0.1";
  FleetReaderOptions fleet;
  std::string static_dir;  // empty: the installed page
  size_t max_clients = 32;
  double duration_s = 0.0;  // 0: until SIGINT or SIGTERM
};

// Serves until a signal (or the duration); prints the URL to open on `out` once listening.
// kExitOk; kExitBadInput for a bad option, a folder without the page or an address it cannot bind.
int RunView(const ViewOptions& options, std::ostream& out, std::ostream& err);

// The view also takes its options from a config file (--config, ROS 2 node name fleetmap_view)
// and the environment: pass the returned command to config::ParseCommandLine.
std::shared_ptr<config::ConfigurableCommand> AddViewCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
