#include "common/route_graph/route_graph_builder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "common/route_graph/route_planner.hpp"
#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

using testing::Fill;
using testing::SegmentExactClearance;
using testing::SolidGrid;
using testing::TwoRooms;

RouteGraphOptions Options(double radius = 0.3) {
  RouteGraphOptions options;
  options.robot_radius = radius;
  return options;
}

int CountKind(const RouteGraph& graph, RouteNodeKind kind) {
  return static_cast<int>(std::count_if(graph.nodes.begin(), graph.nodes.end(),
                                        [kind](const RouteNode& n) { return n.kind == kind; }));
}

std::map<uint32_t, int> Degrees(const RouteGraph& graph) {
  std::map<uint32_t, int> degree;
  for (const RouteNode& node : graph.nodes) degree[node.id] = 0;
  for (const RouteEdge& edge : graph.edges) {
    ++degree[edge.start];
    ++degree[edge.end];
  }
  return degree;
}

bool AllConnected(const RouteGraph& graph) {
  const RoutePlanner planner(graph);
  for (const RouteNode& node : graph.nodes) {
    if (!planner.Connected(graph.nodes.front().id, node.id)) return false;
  }
  return true;
}

void ExpectEdgesKeepRadius(const grid::OccupancyGrid& grid, const RouteGraph& graph) {
  for (const RouteEdge& edge : graph.edges) {
    const Point2 a = graph.FindNode(edge.start)->position;
    const Point2 b = graph.FindNode(edge.end)->position;
    const double exact = SegmentExactClearance(grid, a, b, 1.0);
    EXPECT_GE(exact, graph.robot_radius) << "edge " << edge.id;
    EXPECT_LE(std::min(edge.clearance, 1.0), exact + 1e-9)
        << "edge " << edge.id << " claims more than it has";
  }
}

TEST(RouteGraphBuilderTest, CorridorIsOneLineOfLanesBetweenTwoDeadEnds) {
  grid::OccupancyGrid grid = SolidGrid(22.0, 3.0);
  Fill(&grid, 1.0, 0.7, 21.0, 2.3);  // 20 m long, 1.6 m wide
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_EQ(CountKind(*graph, RouteNodeKind::kDeadEnd), 2);
  EXPECT_EQ(CountKind(*graph, RouteNodeKind::kJunction), 0);
  EXPECT_EQ(graph->edges.size() + 1, graph->nodes.size()) << "a corridor is a path";
  EXPECT_TRUE(AllConnected(*graph));
  double length = 0.0;
  for (const RouteEdge& edge : graph->edges) {
    EXPECT_LE(edge.length, builder.options().lane_spacing + 1e-9);
    length += edge.length;
  }
  // Between the middles of the corridor's two ends: 20 m less its half width (0.8 m) at each end.
  EXPECT_NEAR(length, 20.0 - 2 * 0.8, 0.15);
  for (const RouteNode& node : graph->nodes) EXPECT_NEAR(node.position.y(), 1.5, 0.06);
  ExpectEdgesKeepRadius(grid, *graph);
  EXPECT_TRUE(graph->message.empty()) << graph->message;
}

TEST(RouteGraphBuilderTest, TwoRoomsMeetAtADoorwayNode) {
  const grid::OccupancyGrid grid = TwoRooms(1.0);
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(AllConnected(*graph));
  std::vector<Point2> doorways;
  for (const RouteNode& node : graph->nodes) {
    if (node.kind == RouteNodeKind::kDoorway) doorways.push_back(node.position);
  }
  ASSERT_EQ(doorways.size(), 1U);
  EXPECT_NEAR(doorways[0].x(), 7.1, 0.15);
  EXPECT_NEAR(doorways[0].y(), 4.0, 0.1);
  // Each room has a node in its middle (where its skeleton shrinks to).
  int left = 0;
  int right = 0;
  for (const RouteNode& node : graph->nodes) {
    if ((node.position - Point2(4.0, 4.0)).norm() < 0.3) ++left;
    if ((node.position - Point2(10.2, 4.0)).norm() < 0.3) ++right;
  }
  EXPECT_EQ(left, 1);
  EXPECT_EQ(right, 1);
  ExpectEdgesKeepRadius(grid, *graph);
  // Sparse: two 36 m^2 rooms need no more than a node per 5 m^2.
  EXPECT_LE(graph->nodes.size(), 72U / 5U);
}

TEST(RouteGraphBuilderTest, NodesCloserThanTheRobotsDiameterBecomeOne) {
  // A tile border 0.2 m past the doorway cuts the curve there too: two nodes 0.2 m apart.
  const grid::OccupancyGrid grid = TwoRooms(1.0);
  RouteGraphOptions apart = Options();
  apart.tile_size = 7.3;
  apart.min_node_distance = 0.01;
  const StatusOr<RouteGraph> both = RouteGraphBuilder(apart).Build(grid);
  ASSERT_TRUE(both.ok()) << both.status();
  const auto near_door = [](const RouteGraph& graph) {
    return std::count_if(graph.nodes.begin(), graph.nodes.end(), [](const RouteNode& node) {
      return (node.position - Point2(7.2, 4.0)).norm() < 0.5;
    });
  };
  ASSERT_EQ(near_door(*both), 2) << "the setting must give two nodes at the door";

  RouteGraphOptions merged = apart;
  merged.min_node_distance = 0.0;  // the robot's diameter, 0.6 m
  const StatusOr<RouteGraph> one = RouteGraphBuilder(merged).Build(grid);
  ASSERT_TRUE(one.ok()) << one.status();
  EXPECT_EQ(near_door(*one), 1);
  EXPECT_EQ(CountKind(*one, RouteNodeKind::kDoorway), 1) << "the doorway is the node that stays";
  EXPECT_EQ(one->nodes.size() + 1, both->nodes.size());
  for (const RouteEdge& edge : one->edges) EXPECT_GE(edge.length, 0.6) << "edge " << edge.id;
  EXPECT_TRUE(AllConnected(*one));
  ExpectEdgesKeepRadius(grid, *one);
}

TEST(RouteGraphBuilderTest, CrossroadsIsOneJunctionOfFourCorridors) {
  grid::OccupancyGrid grid = SolidGrid(20.0, 20.0);
  Fill(&grid, 1.0, 9.2, 19.0, 10.8);
  Fill(&grid, 9.2, 1.0, 10.8, 19.0);
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  const std::map<uint32_t, int> degree = Degrees(*graph);
  std::vector<const RouteNode*> junctions;
  for (const RouteNode& node : graph->nodes) {
    if (node.kind == RouteNodeKind::kJunction) junctions.push_back(&node);
  }
  ASSERT_EQ(junctions.size(), 1U);
  EXPECT_LT((junctions[0]->position - Point2(10.0, 10.0)).norm(), 0.3);
  EXPECT_EQ(degree.at(junctions[0]->id), 4);
  EXPECT_EQ(CountKind(*graph, RouteNodeKind::kDeadEnd), 4);
  EXPECT_TRUE(AllConnected(*graph));
  ExpectEdgesKeepRadius(grid, *graph);
}

TEST(RouteGraphBuilderTest, PillarInARoomLeavesALoopAroundIt) {
  grid::OccupancyGrid grid = SolidGrid(12.0, 12.0);
  Fill(&grid, 1.0, 1.0, 11.0, 11.0);
  Fill(&grid, 5.0, 5.0, 7.0, 7.0, grid::kOccupiedValue);
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(AllConnected(*graph));
  // A connected graph with a cycle has at least as many edges as nodes.
  EXPECT_GE(graph->edges.size(), graph->nodes.size());
  ExpectEdgesKeepRadius(grid, *graph);
  for (const RouteEdge& edge : graph->edges) {
    EXPECT_GE(edge.clearance, builder.EdgeClearance());
  }
}

TEST(RouteGraphBuilderTest, UnknownSpaceIsNotTraversable) {
  grid::OccupancyGrid grid = TwoRooms(1.0);
  Fill(&grid, 7.0, 3.5, 7.2, 4.5, grid::kUnknownValue);  // the door never observed
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_FALSE(AllConnected(*graph));
  for (const RouteEdge& edge : graph->edges) {
    const double left = graph->FindNode(edge.start)->position.x();
    const double right = graph->FindNode(edge.end)->position.x();
    EXPECT_EQ(left < 7.0, right < 7.0) << "edge " << edge.id << " crosses unknown space";
  }
  EXPECT_THAT(graph->message, ::testing::HasSubstr("2 parts not connected"));
}

TEST(RouteGraphBuilderTest, RobotWiderThanEveryPassageGivesAnEmptyGraphWithAMessage) {
  grid::OccupancyGrid grid = SolidGrid(12.0, 12.0);
  Fill(&grid, 1.0, 5.6, 11.0, 6.4);  // 0.8 m corridors with 0.8 m doors
  Fill(&grid, 5.6, 1.0, 6.4, 11.0);
  // Where the corridors cross, the walls' corners are 0.57 m from the middle: 0.55 + 0.05 is more.
  RouteGraphBuilder builder(Options(0.55));
  const StatusOr<RouteGraph> graph = builder.Build(grid);
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(graph->nodes.empty());
  EXPECT_TRUE(graph->edges.empty());
  EXPECT_THAT(graph->message, ::testing::HasSubstr("empty route graph"));
  EXPECT_THAT(graph->message, ::testing::HasSubstr("radius 0.55 m"));
  EXPECT_THAT(graph->message, ::testing::HasSubstr("fits nowhere"));

  // Larger than the default exact clearance (3 m): still an empty graph saying why, not an error.
  RouteGraphBuilder huge(Options(5.0));
  const StatusOr<RouteGraph> none = huge.Build(grid);
  ASSERT_TRUE(none.ok()) << none.status();
  EXPECT_TRUE(none->nodes.empty());
  EXPECT_THAT(none->message, ::testing::HasSubstr("radius 5 m"));
}

TEST(RouteGraphBuilderTest, RobotWiderThanTheDoorLeavesTheRoomsApart) {
  const grid::OccupancyGrid grid = TwoRooms(0.8);
  RouteGraphBuilder narrow(Options(0.3));
  const StatusOr<RouteGraph> fits = narrow.Build(grid);
  ASSERT_TRUE(fits.ok());
  EXPECT_TRUE(AllConnected(*fits));
  RouteGraphBuilder wide(Options(0.45));
  const StatusOr<RouteGraph> apart = wide.Build(grid);
  ASSERT_TRUE(apart.ok());
  EXPECT_FALSE(apart->nodes.empty());
  EXPECT_FALSE(AllConnected(*apart));
  EXPECT_EQ(CountKind(*apart, RouteNodeKind::kDoorway), 0);
  EXPECT_THAT(apart->message, ::testing::HasSubstr("does not fit through"));
}

TEST(RouteGraphBuilderTest, RoomsOfTheSubmapGraphGetACentreNode) {
  const grid::OccupancyGrid grid = TwoRooms(1.0);
  scene::SubmapGraph rooms;
  scene::Submap room;
  room.navigable = grid::OccupancyGrid(120, 120, 0.05, Pose2{1.0, 1.0, 0.0}, grid::kFreeValue);
  rooms.submaps.push_back(room);
  RouteGraphBuilder builder(Options());
  const StatusOr<RouteGraph> graph = builder.Build(grid, {.rooms = &rooms});
  ASSERT_TRUE(graph.ok());
  std::vector<Point2> centres;
  for (const RouteNode& node : graph->nodes) {
    if (node.kind == RouteNodeKind::kRoomCentre) centres.push_back(node.position);
  }
  ASSERT_EQ(centres.size(), 1U);
  EXPECT_LT((centres[0] - Point2(4.0, 4.0)).norm(), 0.2);
  EXPECT_TRUE(AllConnected(*graph));
}

TEST(RouteGraphBuilderTest, RefusesARotatedOrEmptyGrid) {
  RouteGraphBuilder builder(Options());
  EXPECT_FALSE(builder.Build(grid::OccupancyGrid()).ok());
  grid::OccupancyGrid rotated(10, 10, 0.05, Pose2{0.0, 0.0, 0.3}, grid::kFreeValue);
  const StatusOr<RouteGraph> graph = builder.Build(rotated);
  ASSERT_FALSE(graph.ok());
  EXPECT_THAT(graph.status().message(), ::testing::HasSubstr("rotated"));
  EXPECT_FALSE(builder.Update(rotated, {}).ok());
}

TEST(RouteGraphBuilderTest, OptionsAreValidated) {
  RouteGraphOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.robot_radius = -1.0;
  EXPECT_FALSE(options.Validate().ok());
  options = RouteGraphOptions{};
  options.clearance_cap = 0.0;
  EXPECT_FALSE(options.Validate().ok());
  // A robot larger than the cap raises the exact clearance with it rather than being refused.
  options = RouteGraphOptions{};
  options.robot_radius = 5.0;
  EXPECT_TRUE(options.Validate().ok());
  EXPECT_GE(options.ExactClearanceUpTo(), 6.05);
  options = RouteGraphOptions{};
  options.doorway_ratio = 1.5;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::route_graph
