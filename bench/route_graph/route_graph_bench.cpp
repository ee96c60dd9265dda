#include "bench/route_graph/route_graph_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>

#include "bench/report/report_format.hpp"
#include "bench/route_graph/clearance_judge.hpp"
#include "cli/inputs/command_inputs.hpp"
#include "common/route_graph/grid_planner.hpp"
#include "common/route_graph/route_graph_builder.hpp"
#include "common/route_graph/route_planner.hpp"

namespace fleetmap::bench {
namespace {

using route_graph::ClearanceMap;
using route_graph::GridPlanner;
using route_graph::RouteGraph;
using route_graph::RouteGraphBuilder;
using route_graph::RouteGraphOptions;
using route_graph::RoutePlanner;

double Milliseconds(std::chrono::steady_clock::duration duration) {
  return std::chrono::duration<double, std::milli>(duration).count();
}

bool SegmentKeepsRadius(const grid::OccupancyGrid& grid, const Point2& a, const Point2& b,
                        double radius) {
  return SegmentExactClearance(grid, a, b, radius + grid.resolution()) >= radius;
}

// One tile of the grid (10 m) with the most free cells, and a 0.5 m box at its most open cell:
// the change the update is timed on.
struct TileChange {
  grid::CellRect tile;
  grid::CellRect box;
};

std::optional<TileChange> PickTileChange(const grid::OccupancyGrid& grid,
                                         const ClearanceMap& clearance, double tile_size) {
  const int tile_cells = static_cast<int>(std::lround(tile_size / grid.resolution()));
  std::optional<TileChange> best;
  int64_t best_free = 0;
  for (int ty = 0; ty * tile_cells < grid.height(); ++ty) {
    for (int tx = 0; tx * tile_cells < grid.width(); ++tx) {
      const grid::CellRect tile{tx * tile_cells, ty * tile_cells,
                                std::min(tile_cells, grid.width() - tx * tile_cells),
                                std::min(tile_cells, grid.height() - ty * tile_cells)};
      int64_t free = 0;
      grid::CellIndex open{-1, -1};
      float open_value = 0.0F;
      for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
        for (int x = tile.x0; x < tile.x0 + tile.width; ++x) {
          if (grid.StateAt(x, y) != grid::CellState::kFree) continue;
          ++free;
          if (clearance.at(x, y) > open_value) {
            open_value = clearance.at(x, y);
            open = {x, y};
          }
        }
      }
      if (free <= best_free || open.x < 0) continue;
      best_free = free;
      const int half = std::max(1, static_cast<int>(std::lround(0.25 / grid.resolution())));
      grid::CellRect box{std::max(open.x - half, tile.x0), std::max(open.y - half, tile.y0),
                         2 * half, 2 * half};
      box.width = std::min(box.width, tile.x0 + tile.width - box.x0);
      box.height = std::min(box.height, tile.y0 + tile.height - box.y0);
      best = TileChange{tile, box};
    }
  }
  return best;
}

}  // namespace

double RouteGraphBenchRow::routes_clear_percent() const {
  return routes > 0 ? 100.0 * routes_clear / routes : 0.0;
}

double RouteGraphBenchRow::connected_percent() const {
  return cell_pairs > 0 ? 100.0 * cell_pairs_connected / cell_pairs : 0.0;
}

StatusOr<RouteGraphBenchRow> MeasureRouteGraphBench(const std::string& yaml_path,
                                                    const RouteGraphBenchOptions& options) {
  StatusOr<grid::LoadedMap> loaded = cli::LoadGridInput(yaml_path, cli::kDefaultMaxCells);
  if (!loaded.ok()) return loaded.status();
  if (Status s = cli::CheckAxisAligned(yaml_path, loaded->grid); !s.ok()) return s;
  grid::OccupancyGrid grid = std::move(loaded->grid);
  RouteGraphOptions graph_options;
  graph_options.robot_radius = options.robot_radius;

  RouteGraphBenchRow row;
  row.map = std::filesystem::path(yaml_path).stem().string();
  row.resolution = grid.resolution();
  row.width_m = grid.width() * grid.resolution();
  row.height_m = grid.height() * grid.resolution();
  row.free_m2 =
      static_cast<double>(grid.CountStates().free) * grid.resolution() * grid.resolution();

  // Build: the median of fresh builds.
  std::vector<double> build_times;
  RouteGraphBuilder builder(graph_options);
  RouteGraph graph;
  for (int run = 0; run < options.runs; ++run) {
    RouteGraphBuilder fresh(graph_options);
    const auto start = std::chrono::steady_clock::now();
    StatusOr<RouteGraph> built = fresh.Build(grid);
    build_times.push_back(Milliseconds(std::chrono::steady_clock::now() - start));
    if (!built.ok()) return built.status().WithContext(yaml_path);
  }
  row.build_ms = Median(build_times);
  // A 100 x 100 m map at 0.05 m has 4 million cells; the build is linear in cells.
  row.build_ms_per_hectare = row.build_ms * 4e6 / static_cast<double>(grid.cell_count());
  {
    StatusOr<RouteGraph> built = builder.Build(grid);
    if (!built.ok()) return built.status().WithContext(yaml_path);
    graph = std::move(built).value();
  }
  row.nodes = static_cast<int>(graph.nodes.size());
  row.edges = static_cast<int>(graph.edges.size());
  row.nodes_per_5m2 = row.free_m2 > 0.0 ? row.nodes / (row.free_m2 / 5.0) : 0.0;

  const RoutePlanner planner(graph);
  {
    std::map<uint32_t, bool> seen;
    for (const route_graph::RouteNode& node : graph.nodes) {
      bool first = true;
      for (const auto& [id, unused] : seen) {
        (void)unused;
        if (planner.Connected(id, node.id)) {
          first = false;
          break;
        }
      }
      if (first) seen[node.id] = true;
    }
    row.graph_parts = static_cast<int>(seen.size());
  }
  std::mt19937 random(options.seed);

  // Routes between random node pairs, each edge judged on the grid.
  if (!graph.nodes.empty()) {
    std::map<std::pair<uint32_t, uint32_t>, bool> judged;
    std::uniform_int_distribution<size_t> pick(0, graph.nodes.size() - 1);
    for (int attempt = 0; attempt < 20 * options.route_pairs && row.routes < options.route_pairs;
         ++attempt) {
      const uint32_t from = graph.nodes[pick(random)].id;
      const uint32_t to = graph.nodes[pick(random)].id;
      if (from == to) continue;
      const std::optional<route_graph::Route> route = planner.Plan(from, to);
      if (!route) continue;
      ++row.routes;
      bool clear = true;
      for (size_t i = 1; i < route->nodes.size(); ++i) {
        const auto key = std::minmax(route->nodes[i - 1], route->nodes[i]);
        auto found = judged.find(key);
        if (found == judged.end()) {
          const bool keeps =
              SegmentKeepsRadius(grid, graph.FindNode(key.first)->position,
                                 graph.FindNode(key.second)->position, options.robot_radius);
          found = judged.emplace(key, keeps).first;
        }
        clear = clear && found->second;
      }
      row.routes_clear += clear ? 1 : 0;
    }
  }

  // Cell pairs the inflated grid connects: connected in the graph? How much longer?
  const ClearanceMap& clearance = builder.clearance();
  const GridPlanner grid_planner(clearance, builder.NodeClearance());
  const std::vector<grid::CellIndex> cells = grid_planner.TraversableCells();
  std::vector<double> ratios;
  std::vector<double> nearest_ratios;
  if (!cells.empty()) {
    std::uniform_int_distribution<size_t> pick(0, cells.size() - 1);
    for (int attempt = 0; attempt < 20 * options.cell_pairs && row.cell_pairs < options.cell_pairs;
         ++attempt) {
      const grid::CellIndex a = cells[pick(random)];
      const grid::CellIndex b = cells[pick(random)];
      if (grid_planner.Component(a) != grid_planner.Component(b)) continue;
      ++row.cell_pairs;
      const Point2 pa = clearance.CellCenter(a.x, a.y);
      const Point2 pb = clearance.CellCenter(b.x, b.y);
      const std::optional<uint32_t> entry_a = planner.Entry(pa, clearance, builder.EdgeClearance());
      const std::optional<uint32_t> entry_b = planner.Entry(pb, clearance, builder.EdgeClearance());
      if (!entry_a || !entry_b || !planner.Connected(*entry_a, *entry_b)) continue;
      ++row.cell_pairs_connected;
      if (row.length_pairs >= options.length_pairs) continue;
      const std::optional<double> grid_length = grid_planner.PathLength(a, b);
      if (!grid_length || *grid_length < 1.0) continue;  // a metre at least, or ratios mean little
      const std::optional<double> graph_length =
          planner.ShortestWay(pa, pb, clearance, builder.EdgeClearance());
      if (!graph_length) continue;
      const std::optional<route_graph::Route> nearest = planner.Plan(*entry_a, *entry_b);
      const double nearest_length = (graph.FindNode(*entry_a)->position - pa).norm() +
                                    nearest->length +
                                    (graph.FindNode(*entry_b)->position - pb).norm();
      nearest_ratios.push_back(nearest_length / *grid_length);
      ratios.push_back(*graph_length / *grid_length);
      ++row.length_pairs;
    }
  }
  row.median_length_ratio = Median(ratios);
  row.median_nearest_ratio = Median(nearest_ratios);

  // One tile changed: a box put down at its most open cell, then taken away; each update timed.
  const std::optional<TileChange> change = PickTileChange(grid, clearance, graph_options.tile_size);
  if (change) {
    const grid::OccupancyGrid original = grid;
    // Puts the box down and takes it away options.runs times, each update timed; with `object`,
    // the box is a learned movable object, in the overlay while it stands (the server's overlay,
    // docs/route-graph.md: the update opens its cells and marks the edges through it).
    const auto time_updates =
        [&](const std::optional<route_graph::MovableObject>& object) -> StatusOr<double> {
      std::vector<double> times;
      for (int run = 0; run < options.runs; ++run) {
        for (const bool put : {true, false}) {
          for (int y = change->box.y0; y < change->box.y0 + change->box.height; ++y) {
            for (int x = change->box.x0; x < change->box.x0 + change->box.width; ++x) {
              grid.at(x, y) = put ? grid::kOccupiedValue : original.at(x, y);
            }
          }
          const auto start = std::chrono::steady_clock::now();
          const route_graph::RouteOverlay overlay =
              put && object ? route_graph::RouteOverlay::Make(grid, {}, {*object})
                            : route_graph::RouteOverlay();
          StatusOr<RouteGraph> updated =
              builder.Update(grid, {change->tile}, {.overlay = &overlay});
          times.push_back(Milliseconds(std::chrono::steady_clock::now() - start));
          if (!updated.ok()) return updated.status().WithContext(yaml_path);
        }
      }
      return Median(times);
    };
    FLEETMAP_ASSIGN_OR_RETURN(row.update_ms, time_updates(std::nullopt));
    route_graph::MovableObject box;
    box.patch.width = change->box.width;
    box.patch.height = change->box.height;
    box.patch.resolution = grid.resolution();
    box.patch.occupancy.assign(static_cast<size_t>(box.patch.width) * box.patch.height, 1.0F);
    const Point2 corner = grid.CellCenter(change->box.x0, change->box.y0);
    const Point2 far = grid.CellCenter(change->box.x0 + change->box.width - 1,
                                       change->box.y0 + change->box.height - 1);
    const Point2 centre = 0.5 * (corner + far);
    box.sightings = {Pose2{centre.x(), centre.y(), 0.0}};
    FLEETMAP_ASSIGN_OR_RETURN(row.update_object_ms, time_updates(box));
  }
  return row;
}

std::vector<RouteGraphTarget> EvaluateRouteGraphTargets(
    const std::vector<RouteGraphBenchRow>& rows) {
  std::vector<RouteGraphTarget> targets;
  double worst_clear = 100.0;
  double worst_connected = 100.0;
  double worst_ratio = 0.0;
  double worst_build = 0.0;
  double worst_update = 0.0;
  std::vector<double> densities;
  for (const RouteGraphBenchRow& row : rows) {
    worst_clear = std::min(worst_clear, row.routes_clear_percent());
    worst_connected = std::min(worst_connected, row.connected_percent());
    worst_ratio = std::max(worst_ratio, row.median_length_ratio);
    worst_build = std::max(worst_build, row.build_ms_per_hectare);
    worst_update = std::max(worst_update, row.update_ms);
    densities.push_back(row.nodes_per_5m2);
  }
  targets.push_back({"sampled graph routes collision-free at the radius = 100 % on every map",
                     "worst " + Fixed(worst_clear, 1) + " %", worst_clear >= 100.0});
  targets.push_back({"grid-connected cell pairs connected in the graph >= 98 % on every map",
                     "worst " + Fixed(worst_connected, 1) + " %", worst_connected >= 98.0});
  targets.push_back(
      {"graph route / A* route <= 1.2 on median, on every map (joined at the best of 4 nodes)",
       "worst " + Fixed(worst_ratio, 3), worst_ratio <= 1.2});
  const double density = Median(densities);
  targets.push_back(
      {"nodes per 5 m^2 of free space <= 1, median over maps", Fixed(density, 3), density <= 1.0});
  targets.push_back({"build time of a 100 x 100 m map at 0.05 m <= 1 s (scaled by cells)",
                     "worst " + Fixed(worst_build, 0) + " ms", worst_build <= 1000.0});
  targets.push_back({"one-tile update <= 50 ms", "worst " + Fixed(worst_update, 1) + " ms",
                     worst_update <= 50.0});
  return targets;
}

void PrintRouteGraphBench(const std::vector<RouteGraphBenchRow>& rows,
                          const std::vector<RouteGraphTarget>& targets,
                          const RouteGraphBenchOptions& options, std::ostream& out) {
  out << "Route graph (radius " << options.robot_radius
      << " m) against A* on the inflated grid\n\n";
  out << "| map | size (m) | free (m^2) | nodes | edges | parts | nodes / 5 m^2 | routes clear | "
         "cell pairs connected | median length / A* | via nearest node | build (ms) | per 100x100 "
         "m at 0.05 m (ms) | "
         "one-tile update (ms) | the same as a movable object (ms) |\n";
  out << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const RouteGraphBenchRow& row : rows) {
    out << "| " << row.map << " | " << Fixed(row.width_m, 1) << " x " << Fixed(row.height_m, 1)
        << " | " << Fixed(row.free_m2, 0) << " | " << row.nodes << " | " << row.edges << " | "
        << row.graph_parts << " | " << Fixed(row.nodes_per_5m2, 3) << " | " << row.routes_clear
        << " / " << row.routes << " (" << Fixed(row.routes_clear_percent(), 1) << " %) | "
        << row.cell_pairs_connected << " / " << row.cell_pairs << " ("
        << Fixed(row.connected_percent(), 1) << " %) | " << Fixed(row.median_length_ratio, 3)
        << " (" << row.length_pairs << ") | " << Fixed(row.median_nearest_ratio, 3) << " | "
        << Fixed(row.build_ms, 1) << " | " << Fixed(row.build_ms_per_hectare, 0) << " | "
        << Fixed(row.update_ms, 1) << " | " << Fixed(row.update_object_ms, 1) << " |\n";
  }
  out << "\nTargets (issue 37):\n\n| target | actual | |\n|---|---|---|\n";
  for (const RouteGraphTarget& target : targets) {
    out << "| " << target.name << " | " << target.actual << " | " << (target.met ? "met" : "MISSED")
        << " |\n";
  }
  out << "\nMachine: " << MachineDescription() << ", Release build.\n";
}

nlohmann::ordered_json RouteGraphBenchJson(const std::vector<RouteGraphBenchRow>& rows,
                                           const std::vector<RouteGraphTarget>& targets,
                                           const RouteGraphBenchOptions& options) {
  nlohmann::ordered_json maps = nlohmann::ordered_json::array();
  for (const RouteGraphBenchRow& row : rows) {
    maps.push_back({{"map", row.map},
                    {"width_m", row.width_m},
                    {"height_m", row.height_m},
                    {"resolution", row.resolution},
                    {"free_m2", row.free_m2},
                    {"nodes", row.nodes},
                    {"edges", row.edges},
                    {"graph_parts", row.graph_parts},
                    {"nodes_per_5m2", row.nodes_per_5m2},
                    {"routes", row.routes},
                    {"routes_clear", row.routes_clear},
                    {"cell_pairs", row.cell_pairs},
                    {"cell_pairs_connected", row.cell_pairs_connected},
                    {"length_pairs", row.length_pairs},
                    {"median_length_ratio", row.median_length_ratio},
                    {"median_length_ratio_via_nearest_node", row.median_nearest_ratio},
                    {"build_ms", row.build_ms},
                    {"build_ms_per_100x100m", row.build_ms_per_hectare},
                    {"one_tile_update_ms", row.update_ms},
                    {"one_tile_update_movable_object_ms", row.update_object_ms}});
  }
  nlohmann::ordered_json judged = nlohmann::ordered_json::array();
  for (const RouteGraphTarget& target : targets) {
    judged.push_back({{"target", target.name}, {"actual", target.actual}, {"met", target.met}});
  }
  return {{"robot_radius", options.robot_radius},
          {"route_pairs", options.route_pairs},
          {"cell_pairs", options.cell_pairs},
          {"runs", options.runs},
          {"seed", options.seed},
          {"machine", MachineDescription()},
          {"maps", maps},
          {"targets", judged}};
}

std::string RouteGraphBenchCsv(const std::vector<RouteGraphBenchRow>& rows) {
  std::ostringstream csv;
  csv << "map,width_m,height_m,free_m2,nodes,edges,graph_parts,nodes_per_5m2,routes,routes_clear,"
         "cell_pairs,cell_pairs_connected,median_length_ratio,median_length_ratio_via_nearest_node,"
         "build_ms,build_ms_per_100x100m,"
         "one_tile_update_ms,one_tile_update_movable_object_ms\n";
  for (const RouteGraphBenchRow& row : rows) {
    csv << row.map << "," << Fixed(row.width_m, 2) << "," << Fixed(row.height_m, 2) << ","
        << Fixed(row.free_m2, 1) << "," << row.nodes << "," << row.edges << "," << row.graph_parts
        << "," << Fixed(row.nodes_per_5m2, 4) << "," << row.routes << "," << row.routes_clear << ","
        << row.cell_pairs << "," << row.cell_pairs_connected << ","
        << Fixed(row.median_length_ratio, 4) << "," << Fixed(row.median_nearest_ratio, 4) << ","
        << Fixed(row.build_ms, 2) << "," << Fixed(row.build_ms_per_hectare, 1) << ","
        << Fixed(row.update_ms, 2) << "," << Fixed(row.update_object_ms, 2) << "\n";
  }
  return csv.str();
}

}  // namespace fleetmap::bench
