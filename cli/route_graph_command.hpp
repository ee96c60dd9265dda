#pragma once

// `fleetmap route-graph MAP.yaml --radius R --out graph.geojson [--rmf-out nav.yaml]`: the route
// graph of a map_server map (common/route_graph, docs/route-graph.md) written as nav2_route's
// GeoJSON graph file and, on request, as an Open-RMF nav graph of one level. A graph in parts that
// do not connect is written, with a note; an empty graph (the robot fits nowhere) is not, and the
// command exits 2 saying why.
// `fleetmap route-graph --live --out graph.geojson`: the graph a running fleetmap-server publishes
// on rt/fleetmap/route_graph instead (its ids, predicted edges and blocking objects as the fleet
// has them), like save-map; exit 1 when none comes within --timeout.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/fleet_reader_options.hpp"
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
  // --live: the fleet's graph, read from rt/fleetmap/route_graph.
  bool live = false;
  std::string graph_id;  // which graph (a shard's); empty: the only one
  double timeout_s = 10.0;
  double settle_s = 0.5;  // after the first graph, for other shards' and newer revisions
  FleetReaderOptions fleet;
  bool err_is_terminal = false;
};

int RunRouteGraph(const RouteGraphCommandOptions& options, std::ostream& out, std::ostream& err);

void AddRouteGraphCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
