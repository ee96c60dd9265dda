#include "cli/route_graph_command.hpp"

#include <algorithm>
#include <iostream>
#include <memory>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/number_format.hpp"
#include "common/route_graph/route_graph_export.hpp"

namespace fleetmap::cli {

int RunRouteGraph(const RouteGraphCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap route-graph: " << message << "\n";
    return kExitBadInput;
  };
  if (options.geojson_path.empty() && options.rmf_path.empty()) {
    return fail("nothing to write: pass --out and/or --rmf-out");
  }
  if (Status s = options.graph.Validate(); !s.ok()) return fail(s.message());
  if (options.rmf_level.empty()) return fail("--level must not be empty");
  StatusOr<grid::LoadedMap> map = LoadGridInput(options.map_yaml, options.max_cells);
  if (!map.ok()) return fail(map.status().message());
  if (Status s = CheckAxisAligned(options.map_yaml, map->grid); !s.ok()) return fail(s.message());

  route_graph::RouteGraphBuilder builder(options.graph);
  StatusOr<route_graph::RouteGraph> graph = builder.Build(map->grid);
  if (!graph.ok()) return fail(options.map_yaml + ": " + graph.status().message());
  if (graph->nodes.empty()) return fail(options.map_yaml + ": " + graph->message);
  if (!graph->message.empty()) err << "fleetmap route-graph: note: " << graph->message << "\n";

  if (!options.geojson_path.empty()) {
    const std::string text = route_graph::Nav2RouteGeoJson(*graph).dump(1) + "\n";
    if (Status s = WriteFileAtomically(options.geojson_path, text); !s.ok()) {
      return fail(s.message());
    }
  }
  if (!options.rmf_path.empty()) {
    const std::string text = route_graph::RmfNavGraphYaml(*graph, options.rmf_level);
    if (Status s = WriteFileAtomically(options.rmf_path, text); !s.ok()) return fail(s.message());
  }
  int counts[5] = {0, 0, 0, 0, 0};
  for (const route_graph::RouteNode& node : graph->nodes) ++counts[static_cast<int>(node.kind)];
  double length = 0.0;
  for (const route_graph::RouteEdge& edge : graph->edges) length += edge.length;
  out << options.map_yaml << " -> ";
  if (!options.geojson_path.empty()) out << options.geojson_path;
  if (!options.geojson_path.empty() && !options.rmf_path.empty()) out << ", ";
  if (!options.rmf_path.empty()) out << options.rmf_path;
  out << ": " << graph->nodes.size() << " nodes (";
  for (int kind = 0; kind < 5; ++kind) {
    out << (kind > 0 ? ", " : "") << counts[kind] << " "
        << route_graph::RouteNodeKindName(static_cast<route_graph::RouteNodeKind>(kind));
  }
  out << "), " << graph->edges.size() << " edges, " << FixedNumber(length, 1)
      << " m of lanes, for a robot of radius " << ShortNumber(options.graph.robot_radius) << " m\n";
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddRouteGraphCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RouteGraphCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "route-graph", "The map as a route graph: nav2_route GeoJSON, Open-RMF nav graph YAML");
  cmd->add_option("map", options->map_yaml, "map_server YAML")->required();
  cmd->add_option("--radius", options->graph.robot_radius, "Robot radius, metres")
      ->capture_default_str();
  cmd->add_option("--margin", options->graph.clearance_margin,
                  "Clearance beyond the radius at nodes, metres (at least one cell is used)")
      ->capture_default_str();
  cmd->add_option("--lane-spacing", options->graph.lane_spacing,
                  "Longest edge along a straight corridor, metres")
      ->capture_default_str();
  cmd->add_option("--frame", options->graph.frame, "Frame of the nodes")->capture_default_str();
  cmd->add_option("--out", options->geojson_path, "Write nav2_route's GeoJSON graph here");
  cmd->add_option("--rmf-out", options->rmf_path, "Write an Open-RMF nav graph YAML here");
  cmd->add_option("--level", options->rmf_level, "The Open-RMF level's name")
      ->capture_default_str();
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback(
      [options, exit_code]() { *exit_code = RunRouteGraph(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
