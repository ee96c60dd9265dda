#pragma once

// `fleetmap bench route-graph`: the route graph (common/route_graph) of a real map against the
// grid planner it replaces for fleet managers (A* on the grid inflated by the robot): how many
// sampled graph routes keep the robot's radius on the grid, how many cell pairs the grid connects
// the graph connects, how much longer its routes are (a straight leg from each cell to one of its
// four nearest nodes it sees, the best of those ways, over A*'s path), how sparse it is, and how
// long a build and a one-tile update take. Judged by a clearance check of its own (the exact
// distance to the nearest blocked cell), not the builder's.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::bench {

struct RouteGraphBenchOptions {
  double robot_radius = 0.25;
  int route_pairs = 200;  // node pairs routed and checked
  int cell_pairs = 500;   // grid-connected cell pairs checked for graph connectivity
  int length_pairs = 40;  // of those, pairs whose route length is compared with A*
  int runs = 3;           // timings are medians of this many
  uint32_t seed = 37;
};

struct RouteGraphBenchRow {
  std::string map;
  double width_m = 0.0;
  double height_m = 0.0;
  double resolution = 0.0;
  double free_m2 = 0.0;
  int nodes = 0;
  int edges = 0;
  int graph_parts = 0;
  double nodes_per_5m2 = 0.0;
  int routes = 0;
  int routes_clear = 0;
  int cell_pairs = 0;
  int cell_pairs_connected = 0;
  int length_pairs = 0;
  double median_length_ratio = 0.0;   // joined at the best of the four nearest nodes seen
  double median_nearest_ratio = 0.0;  // joined at the nearest node seen
  double build_ms = 0.0;
  double update_ms = 0.0;
  double update_object_ms = 0.0;      // the same change, the box a learned movable object (overlay)
  double build_ms_per_hectare = 0.0;  // build time scaled to a 100 x 100 m map at 0.05 m

  double routes_clear_percent() const;
  double connected_percent() const;
};

struct RouteGraphTarget {
  std::string name;
  std::string actual;
  bool met = false;
};

// Measures one map_server map. Errors name the file.
StatusOr<RouteGraphBenchRow> MeasureRouteGraphBench(const std::string& yaml_path,
                                                    const RouteGraphBenchOptions& options);

std::vector<RouteGraphTarget> EvaluateRouteGraphTargets(
    const std::vector<RouteGraphBenchRow>& rows);
void PrintRouteGraphBench(const std::vector<RouteGraphBenchRow>& rows,
                          const std::vector<RouteGraphTarget>& targets,
                          const RouteGraphBenchOptions& options, std::ostream& out);
nlohmann::ordered_json RouteGraphBenchJson(const std::vector<RouteGraphBenchRow>& rows,
                                           const std::vector<RouteGraphTarget>& targets,
                                           const RouteGraphBenchOptions& options);
std::string RouteGraphBenchCsv(const std::vector<RouteGraphBenchRow>& rows);

}  // namespace fleetmap::bench
