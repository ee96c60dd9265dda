#include "common/route_graph/route_planner.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <string>

#include "common/grid/map_io.hpp"
#include "common/route_graph/grid_planner.hpp"
#include "common/route_graph/route_graph_builder.hpp"
#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

constexpr double kRadius = 0.25;

struct RealMap {
  grid::OccupancyGrid grid;
  RouteGraphBuilder builder{[] {
    RouteGraphOptions options;
    options.robot_radius = kRadius;
    return options;
  }()};
  RouteGraph graph;
};

// The real maps small enough for a unit test (they are also in tests/data/maps/real).
class RouteGraphPlannerTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const std::string path = std::string(FLEETMAP_SHARED_MAPS_DIR) + "/" + GetParam() + ".yaml";
    StatusOr<grid::LoadedMap> loaded = grid::LoadMap(path);
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    map_.grid = std::move(loaded->grid);
    StatusOr<RouteGraph> graph = map_.builder.Build(map_.grid);
    ASSERT_TRUE(graph.ok()) << graph.status();
    map_.graph = std::move(graph).value();
    ASSERT_FALSE(map_.graph.nodes.empty()) << map_.graph.message;
  }

  RealMap map_;
};

TEST_P(RouteGraphPlannerTest, EveryEdgeOfShortestRoutesKeepsTheRadiusOnTheGrid) {
  const RouteGraph& graph = map_.graph;
  const RoutePlanner planner(graph);
  std::map<std::pair<uint32_t, uint32_t>, const RouteEdge*> edge_of;
  for (const RouteEdge& edge : graph.edges) {
    edge_of[{edge.start, edge.end}] = &edge;
    edge_of[{edge.end, edge.start}] = &edge;
  }
  std::mt19937 random(37);
  std::uniform_int_distribution<size_t> pick(0, graph.nodes.size() - 1);
  std::set<uint32_t> checked;
  int routes = 0;
  for (int attempt = 0; attempt < 400 && routes < 100; ++attempt) {
    const uint32_t from = graph.nodes[pick(random)].id;
    const uint32_t to = graph.nodes[pick(random)].id;
    const std::optional<Route> route = planner.Plan(from, to);
    if (!route) continue;
    ++routes;
    double length = 0.0;
    for (size_t i = 1; i < route->nodes.size(); ++i) {
      const auto edge = edge_of.find({route->nodes[i - 1], route->nodes[i]});
      ASSERT_NE(edge, edge_of.end()) << "the route jumps between unjoined nodes";
      length += edge->second->length;
      if (!checked.insert(edge->second->id).second) continue;
      const Point2 a = graph.FindNode(route->nodes[i - 1])->position;
      const Point2 b = graph.FindNode(route->nodes[i])->position;
      EXPECT_GE(testing::SegmentExactClearance(map_.grid, a, b, kRadius + 0.1), kRadius)
          << GetParam() << ": edge " << edge->second->id << " from " << a.transpose() << " to "
          << b.transpose();
    }
    EXPECT_NEAR(length, route->length, 1e-6);
  }
  EXPECT_GE(routes, 50) << "too few connected node pairs to judge";
}

TEST_P(RouteGraphPlannerTest, WhatTheInflatedGridConnectsTheGraphConnects) {
  const RouteGraph& graph = map_.graph;
  const RoutePlanner planner(graph);
  const ClearanceMap& clearance = map_.builder.clearance();
  const GridPlanner grid_planner(clearance, map_.builder.NodeClearance());
  // Every pair of nodes in one part of the grid is in one part of the graph.
  std::map<int, uint32_t> first_node_of_part;
  for (const RouteNode& node : graph.nodes) {
    const grid::CellIndex cell = clearance.CellOf(node.position);
    const int part = grid_planner.Component(cell);
    ASSERT_GE(part, 0) << "node " << node.id << " stands where the robot does not fit";
    const auto [first, inserted] = first_node_of_part.emplace(part, node.id);
    if (!inserted) {
      EXPECT_TRUE(planner.Connected(first->second, node.id))
          << GetParam() << ": nodes " << first->second << " and " << node.id
          << " are joined on the grid, not in the graph";
    }
  }
  // Random cells the grid planner connects: a robot on each reaches a node in a straight line, and
  // the two nodes are connected (the target: >= 98 % of such pairs).
  const std::vector<grid::CellIndex> cells = grid_planner.TraversableCells();
  std::mt19937 random(37);
  std::uniform_int_distribution<size_t> pick(0, cells.size() - 1);
  int pairs = 0;
  int connected = 0;
  for (int attempt = 0; attempt < 2000 && pairs < 300; ++attempt) {
    const grid::CellIndex a = cells[pick(random)];
    const grid::CellIndex b = cells[pick(random)];
    if (grid_planner.Component(a) != grid_planner.Component(b)) continue;
    ++pairs;
    const std::optional<uint32_t> entry_a =
        planner.Entry(clearance.CellCenter(a.x, a.y), clearance, map_.builder.EdgeClearance());
    const std::optional<uint32_t> entry_b =
        planner.Entry(clearance.CellCenter(b.x, b.y), clearance, map_.builder.EdgeClearance());
    if (entry_a && entry_b && planner.Connected(*entry_a, *entry_b)) ++connected;
  }
  ASSERT_GE(pairs, 100);
  EXPECT_GE(static_cast<double>(connected) / pairs, 0.98)
      << GetParam() << ": " << connected << " of " << pairs << " grid-connected pairs";
}

INSTANTIATE_TEST_SUITE_P(RealMaps, RouteGraphPlannerTest,
                         ::testing::Values("aws_small_house", "strands_kth", "tb3_world"));

}  // namespace
}  // namespace fleetmap::route_graph
