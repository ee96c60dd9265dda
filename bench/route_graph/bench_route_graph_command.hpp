#pragma once

// `fleetmap bench route-graph --maps DIR [--radius R] [--json F] [--csv F] [--runs N]`: for every
// *.yaml in DIR, the route graph against A* on the inflated grid (route_graph_bench.hpp). Prints a
// Markdown table and the targets met / missed; writes JSON / CSV on request.

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

#include "bench/route_graph/route_graph_bench.hpp"

namespace fleetmap::bench {

struct BenchRouteGraphCommandOptions {
  std::string maps_dir;
  std::string json_path;
  std::string csv_path;
  bool progress = true;
  bool err_is_terminal = false;
  RouteGraphBenchOptions bench;
};

int RunBenchRouteGraph(const BenchRouteGraphCommandOptions& options, std::ostream& out,
                       std::ostream& err);

// Registers `route-graph` under `bench` (see BenchCommand).
void AddBenchRouteGraphCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
