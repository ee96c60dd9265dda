#include "cli/route_graph_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <variant>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/number_format.hpp"
#include "common/core/progress_line.hpp"
#include "common/core/wake_up.hpp"
#include "common/route_graph/route_graph_export.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::cli {
namespace {

using Clock = std::chrono::steady_clock;

// No graph came from the fleet (as save-map's no map).
constexpr int kExitNoGraph = 1;

struct Failure {
  std::string message;
  int exit_code = kExitBadInput;
};

// The graph of the map file, built here.
StatusOr<route_graph::RouteGraph> GraphOfMapFile(const RouteGraphCommandOptions& options) {
  StatusOr<grid::LoadedMap> map = LoadGridInput(options.map_yaml, options.max_cells);
  if (!map.ok()) return map.status();
  FLEETMAP_RETURN_IF_ERROR(CheckAxisAligned(options.map_yaml, map->grid));
  route_graph::RouteGraphBuilder builder(options.graph);
  StatusOr<route_graph::RouteGraph> graph = builder.Build(map->grid);
  if (!graph.ok()) return graph.status().WithContext(options.map_yaml);
  return graph;
}

// The newest graph a running server publishes on rt/fleetmap/route_graph (transient local: a
// server's current graph arrives at once), the one named --graph or the only one.
std::variant<route_graph::RouteGraph, Failure> GraphOfTheFleet(
    const RouteGraphCommandOptions& options, std::ostream& err) {
  auto dds = options.fleet.Participant("fleetmap-route-graph");
  if (!dds.ok()) return Failure{dds.status().message()};
  auto participant = transport::Participant::Create(*dds);
  if (!participant.ok()) return Failure{participant.status().message(), kExitNoGraph};
  const int domain = (*participant)->domain_id();
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RouteGraphReader::Create(**participant, wake_up);
  if (!reader.ok()) return Failure{reader.status().message(), kExitNoGraph};

  std::map<std::string, transport::RouteGraphMessage> graphs;  // by graph id, the newest
  size_t rejected = 0;
  const auto start = Clock::now();
  const auto waited = [&start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const auto waiting = [&] {
    return fmt::format("waiting for the route graph on {} (DDS domain {}): {:.0f} / {:.0f} s",
                       transport::kRouteGraphTopic, domain, waited(), options.timeout_s);
  };
  const auto wanted = [&] {
    return options.graph_id.empty() ? !graphs.empty() : graphs.count(options.graph_id) > 0;
  };
  ProgressLine progress(err, {.terminal = options.err_is_terminal});
  std::optional<double> settled_at;
  double next_note = 0.0;
  while (true) {
    if (settled_at && waited() >= *settled_at) break;
    if (!settled_at && waited() >= options.timeout_s) break;
    if (!settled_at && waited() >= next_note) {
      progress.Update(waiting());
      next_note += 1.0;
    }
    wake_up->WaitFor(std::chrono::milliseconds(100));
    for (transport::RouteGraphEvent& event : (*reader)->Drain()) {
      if (event.kind == transport::RouteGraphEvent::Kind::kRejected) {
        ++rejected;
      } else if (event.kind == transport::RouteGraphEvent::Kind::kRemoved) {
        graphs.erase(event.message.graph_id);
      } else {
        graphs.insert_or_assign(event.message.graph_id, std::move(event.message));
      }
    }
    if (!settled_at && wanted()) {
      settled_at = waited() + options.settle_s;
      progress.Finish(fmt::format("the route graph on {} (DDS domain {}) came after {:.1f} s",
                                  transport::kRouteGraphTopic, domain, waited()));
    }
  }
  if (!settled_at) progress.Finish(waiting());
  reader->reset();
  participant->reset();

  std::string names;
  for (const auto& [id, message] : graphs) names += (names.empty() ? "" : ", ") + id;
  if (!options.graph_id.empty()) {
    const auto found = graphs.find(options.graph_id);
    if (found != graphs.end()) return found->second.graph;
    return Failure{fmt::format("no route graph \"{}\" on {} within {:.0f} s on DDS domain {}{}",
                               options.graph_id, transport::kRouteGraphTopic, options.timeout_s,
                               domain, names.empty() ? "" : " (there are: " + names + ")"),
                   kExitNoGraph};
  }
  if (graphs.size() > 1) {
    return Failure{"the fleet publishes " + std::to_string(graphs.size()) +
                       " route graphs (a sharded fleet): name one with --graph (" + names + ")",
                   kExitBadInput};
  }
  if (graphs.empty()) {
    return Failure{
        fmt::format("no route graph on {} within {:.0f} s on DDS domain {}{}: is a "
                    "fleetmap-server running there with --route-graph (--domain, "
                    "$FLEETMAP_DOMAIN), and is the fleet secured (then --security)?",
                    transport::kRouteGraphTopic, options.timeout_s, domain,
                    rejected > 0 ? fmt::format(" ({} malformed samples refused)", rejected) : ""),
        kExitNoGraph};
  }
  return graphs.begin()->second.graph;
}

}  // namespace

int RunRouteGraph(const RouteGraphCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message, int code = kExitBadInput) {
    err << "fleetmap route-graph: " << message << "\n";
    return code;
  };
  if (options.geojson_path.empty() && options.rmf_path.empty()) {
    return fail("nothing to write: pass --out and/or --rmf-out");
  }
  if (options.live == !options.map_yaml.empty()) {
    return fail("give a map_server YAML or --live (the graph of a running fleet), one of them");
  }
  if (Status s = options.graph.Validate(); !s.ok()) return fail(s.message());
  if (options.rmf_level.empty()) return fail("--level must not be empty");
  const std::string source = options.live ? transport::kRouteGraphTopic : options.map_yaml;
  std::optional<route_graph::RouteGraph> graph;
  if (options.live) {
    auto live = GraphOfTheFleet(options, err);
    if (auto* failure = std::get_if<Failure>(&live)) {
      return fail(failure->message, failure->exit_code);
    }
    graph = std::get<route_graph::RouteGraph>(std::move(live));
  } else {
    StatusOr<route_graph::RouteGraph> built = GraphOfMapFile(options);
    if (!built.ok()) return fail(built.status().message());
    graph = std::move(built).value();
  }
  if (graph->nodes.empty()) {
    return fail(source + ": " + (graph->message.empty() ? "the graph is empty" : graph->message));
  }
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
  out << source << " -> ";
  if (!options.geojson_path.empty()) out << options.geojson_path;
  if (!options.geojson_path.empty() && !options.rmf_path.empty()) out << ", ";
  if (!options.rmf_path.empty()) out << options.rmf_path;
  out << ": " << graph->nodes.size() << " nodes (";
  for (int kind = 0; kind < 5; ++kind) {
    out << (kind > 0 ? ", " : "") << counts[kind] << " "
        << route_graph::RouteNodeKindName(static_cast<route_graph::RouteNodeKind>(kind));
  }
  const auto predicted = std::count_if(graph->edges.begin(), graph->edges.end(),
                                       [](const route_graph::RouteEdge& e) { return e.predicted; });
  const auto blocked =
      std::count_if(graph->edges.begin(), graph->edges.end(),
                    [](const route_graph::RouteEdge& e) { return e.blocking_object.has_value(); });
  out << "), " << graph->edges.size() << " edges";
  if (predicted + blocked > 0) {
    out << " (" << predicted << " through predicted space, " << blocked
        << " blocked by learned objects)";
  }
  out << ", " << FixedNumber(length, 1) << " m of lanes, for a robot of radius "
      << ShortNumber(graph->robot_radius) << " m\n";
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddRouteGraphCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RouteGraphCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "route-graph", "The map as a route graph: nav2_route GeoJSON, Open-RMF nav graph YAML");
  cmd->add_option("map", options->map_yaml, "map_server YAML (or --live)");
  cmd->add_flag("--live", options->live,
                "the graph a running fleetmap-server --route-graph publishes on "
                "rt/fleetmap/route_graph, instead of a map file");
  cmd->add_option("--graph", options->graph_id,
                  "with --live: which graph (a sharded fleet has one per shard)");
  cmd->add_option("--timeout", options->timeout_s, "with --live: seconds to wait for the graph")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
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
  auto fleet = std::make_shared<FleetReaderFlags>(cmd, &options->fleet);
  cmd->callback([options, fleet, exit_code]() {
    fleet->ApplyDomain();
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunRouteGraph(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
