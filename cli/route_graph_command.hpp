#pragma once

// `fleetmap route-graph MAP.yaml --radius R --out graph.geojson [--rmf-out nav.yaml]`: the route
// graph of a map_server map (common/route_graph, docs/route-graph.md) written as nav2_route's
// GeoJSON graph file and, on request, as an Open-RMF nav graph of one level. A graph in parts that
// do not connect is written, with a note; an empty graph (the robot fits nowhere) is not, and the
// command exits 2 saying why.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"
#include "common/route_graph/route_graph_builder.hpp"

namespace fleetmap::cli {

struct RouteGraphCommandOptions {
  std::string map_yaml;
  std::string geojson_path;
  std::string rmf_path;
  std::string rmf_level = "L1";
  route_graph::RouteGraphOptions graph;
  int64_t max_cells = kDefaultMaxCells;
};

int RunRouteGraph(const RouteGraphCommandOptions& options, std::ostream& out, std::ostream& err);

void AddRouteGraphCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
