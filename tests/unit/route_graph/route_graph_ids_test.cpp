#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/route_graph/route_graph_builder.hpp"
#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

using testing::Fill;
using testing::SolidGrid;

// A 40 x 40 m floor: a lattice of 1.6 m corridors every 10 m with a 4 x 4 m room off each
// stretch of corridor, through a 1 m door.
grid::OccupancyGrid Floor() {
  grid::OccupancyGrid grid = SolidGrid(40.0, 40.0);
  for (const double c : {4.2, 14.2, 24.2, 34.2}) {
    Fill(&grid, 1.0, c, 39.0, c + 1.6);
    Fill(&grid, c, 1.0, c + 1.6, 39.0);
  }
  for (const double rx : {6.5, 16.5, 26.5}) {
    for (const double ry : {6.5, 16.5, 26.5}) {
      Fill(&grid, rx, ry + 0.2, rx + 4.0, ry + 4.2);
      Fill(&grid, rx + 1.5, ry - 0.7, rx + 2.5, ry + 0.2);  // the door to the corridor below
    }
  }
  return grid;
}

// The cells of the tile [x0, x0 + 10) x [y0, y0 + 10) m.
grid::CellRect TileCells(const grid::OccupancyGrid& grid, double x0, double y0) {
  const int cells = static_cast<int>(std::lround(10.0 / grid.resolution()));
  return {static_cast<int>(std::lround(x0 / grid.resolution())),
          static_cast<int>(std::lround(y0 / grid.resolution())), cells, cells};
}

// Distance from a point to the square [x0, x0 + size] x [y0, y0 + size].
double DistanceToSquare(const Point2& p, double x0, double y0, double size) {
  const double dx = std::max({x0 - p.x(), 0.0, p.x() - (x0 + size)});
  const double dy = std::max({y0 - p.y(), 0.0, p.y() - (y0 + size)});
  return std::hypot(dx, dy);
}

TEST(RouteGraphIdsTest, AChangeInOneTileKeepsIdsOutsideItsNeighbourhood) {
  grid::OccupancyGrid grid = Floor();
  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> before = builder.Build(grid);
  ASSERT_TRUE(before.ok()) << before.status();
  ASSERT_TRUE(before->message.empty()) << before->message;

  // A pallet left in the corridor of tile (2, 1): the corridor narrows to 0.7 m beside it, too
  // narrow for the robot, and the room's door in that tile is shut.
  Fill(&grid, 24.2, 14.2, 25.1, 15.8, grid::kOccupiedValue);
  Fill(&grid, 28.0, 15.8, 29.0, 16.7, grid::kOccupiedValue);
  const StatusOr<RouteGraph> after = builder.Update(grid, {TileCells(grid, 20.0, 10.0)});
  ASSERT_TRUE(after.ok()) << after.status();

  std::map<uint32_t, const RouteNode*> after_nodes;
  for (const RouteNode& node : after->nodes) after_nodes[node.id] = &node;
  std::map<uint32_t, const RouteEdge*> after_edges;
  for (const RouteEdge& edge : after->edges) after_edges[edge.id] = &edge;

  // Outside the changed tile grown by one tile, everything is as it was, ids included.
  int kept_nodes = 0;
  std::map<uint32_t, bool> far;
  for (const RouteNode& node : before->nodes) {
    far[node.id] = DistanceToSquare(node.position, 20.0, 10.0, 10.0) > 10.0;
    if (!far[node.id]) continue;
    const auto found = after_nodes.find(node.id);
    ASSERT_NE(found, after_nodes.end()) << "node " << node.id << " lost its id";
    EXPECT_EQ(found->second->position, node.position);
    ++kept_nodes;
  }
  int kept_edges = 0;
  for (const RouteEdge& edge : before->edges) {
    if (!far[edge.start] || !far[edge.end]) continue;
    const auto found = after_edges.find(edge.id);
    ASSERT_NE(found, after_edges.end()) << "edge " << edge.id << " lost its id";
    EXPECT_EQ(found->second->start, edge.start);
    EXPECT_EQ(found->second->end, edge.end);
    EXPECT_EQ(found->second->reverse_id, edge.reverse_id);
    ++kept_edges;
  }
  EXPECT_GT(kept_nodes, 20);
  EXPECT_GT(kept_edges, 20);

  // The change itself shows: no edge passes the pallet any more.
  for (const RouteEdge& edge : after->edges) {
    const Point2 a = after->FindNode(edge.start)->position;
    const Point2 b = after->FindNode(edge.end)->position;
    const bool crosses = (std::min(a.x(), b.x()) < 24.6 && std::max(a.x(), b.x()) > 24.6) &&
                         std::abs(a.y() - 15.0) < 0.8 && std::abs(b.y() - 15.0) < 0.8;
    EXPECT_FALSE(crosses) << "edge " << edge.id << " still passes the pallet";
  }
  // New geometry took fresh ids: none reused an id of something that went.
  std::map<uint32_t, bool> before_ids;
  for (const RouteNode& node : before->nodes) before_ids[node.id] = true;
  for (const RouteEdge& edge : before->edges)
    before_ids[edge.id] = before_ids[edge.reverse_id] = true;
  for (const RouteNode& node : after->nodes) {
    if (before_ids.count(node.id) == 0) continue;
    const RouteNode* old = before->FindNode(node.id);
    ASSERT_NE(old, nullptr) << "id " << node.id << " was an edge's";
    EXPECT_EQ(old->position, node.position);
  }
}

TEST(RouteGraphIdsTest, AnUpdateWithNothingChangedKeepsEveryId) {
  const grid::OccupancyGrid grid = Floor();
  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> before = builder.Build(grid);
  ASSERT_TRUE(before.ok());
  const StatusOr<RouteGraph> after = builder.Update(grid, {TileCells(grid, 10.0, 10.0)});
  ASSERT_TRUE(after.ok());
  ASSERT_EQ(after->nodes.size(), before->nodes.size());
  ASSERT_EQ(after->edges.size(), before->edges.size());
  for (size_t i = 0; i < before->nodes.size(); ++i) {
    EXPECT_EQ(after->nodes[i].id, before->nodes[i].id);
    EXPECT_EQ(after->nodes[i].position, before->nodes[i].position);
  }
  for (size_t i = 0; i < before->edges.size(); ++i) {
    EXPECT_EQ(after->edges[i].id, before->edges[i].id);
  }
}

TEST(RouteGraphIdsTest, AFullRebuildOfTheSameMapKeepsEveryId) {
  const grid::OccupancyGrid grid = Floor();
  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> first = builder.Build(grid);
  const StatusOr<RouteGraph> second = builder.Build(grid);
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(second.ok());
  ASSERT_EQ(first->nodes.size(), second->nodes.size());
  for (size_t i = 0; i < first->nodes.size(); ++i) {
    EXPECT_EQ(first->nodes[i].id, second->nodes[i].id);
  }
}

TEST(RouteGraphIdsTest, UpdateNeedsABuildOfTheSameGeometry) {
  const grid::OccupancyGrid grid = Floor();
  RouteGraphBuilder builder(RouteGraphOptions{});
  EXPECT_FALSE(builder.Update(grid, {}).ok());
  ASSERT_TRUE(builder.Build(grid).ok());
  const grid::OccupancyGrid smaller = SolidGrid(20.0, 20.0);
  const StatusOr<RouteGraph> graph = builder.Update(smaller, {});
  ASSERT_FALSE(graph.ok());
  EXPECT_THAT(graph.status().message(), ::testing::HasSubstr("another geometry"));
}

}  // namespace
}  // namespace fleetmap::route_graph
