// The route graph through predicted free space and learned movable objects (issue 37): such
// edges exist, marked, and only such edges are marked.

#include "common/route_graph/route_overlay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>

#include "common/route_graph/route_graph_builder.hpp"
#include "common/route_graph/route_graph_export.hpp"
#include "common/route_graph/route_planner.hpp"
#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

using testing::Fill;
using testing::TwoRooms;

// The right-hand room of TwoRooms, x in [7.2, 13.2), y in [1, 7), as a predicted sub-map: free
// space the server predicts behind the door, in the sub-map's own frame.
PredictedSpace PredictedRightRoom() {
  PredictedSpace room;
  room.submap.kind = scene::SubmapKind::kPredictedDoor;
  room.submap.map_from_submap = Pose2{7.2, 1.0, 0.0};
  room.submap.navigable = grid::OccupancyGrid(120, 120, 0.05, Pose2{}, grid::kFreeValue);
  return room;
}

// TwoRooms with the right-hand room not yet seen (unknown), but for an observed pillar in it.
grid::OccupancyGrid RightRoomUnseen() {
  grid::OccupancyGrid grid = TwoRooms(1.0);
  Fill(&grid, 7.2, 1.0, 13.2, 7.0, grid::kUnknownValue);
  Fill(&grid, 11.0, 5.5, 11.5, 6.0, grid::kOccupiedValue);
  return grid;
}

// A cart standing in TwoRooms' door: the door's cells occupied, and the learned object whose
// footprint covers them.
MovableObject CartInTheDoor(uint32_t id) {
  MovableObject cart;
  cart.id = id;
  cart.patch.width = 4;  // 0.2 x 1 m: the door's cells exactly
  cart.patch.height = 20;
  cart.patch.resolution = 0.05;
  cart.patch.occupancy.assign(4 * 20, 1.0F);
  cart.sightings = {Pose2{7.1, 4.0, 0.0}};
  return cart;
}

int64_t CellIndex(const grid::OccupancyGrid& grid, const Point2& point) {
  const std::optional<grid::CellIndex> cell = grid.CellAt(point);
  EXPECT_TRUE(cell.has_value());
  return static_cast<int64_t>(cell->y) * grid.width() + cell->x;
}

bool Connected(const RouteGraph& graph, double x_left, double x_right) {
  const RoutePlanner planner(graph);
  for (const RouteNode& a : graph.nodes) {
    for (const RouteNode& b : graph.nodes) {
      if (a.position.x() < x_left && b.position.x() > x_right && planner.Connected(a.id, b.id)) {
        return true;
      }
    }
  }
  return false;
}

TEST(RouteOverlayTest, PredictsOnlyUnknownCellsAndObjectsOnlyOnOccupiedOnes) {
  grid::OccupancyGrid grid = RightRoomUnseen();
  Fill(&grid, 7.0, 3.5, 7.2, 4.5, grid::kOccupiedValue);  // the cart in the door
  const RouteOverlay overlay =
      RouteOverlay::Make(grid, {PredictedRightRoom()}, {CartInTheDoor(42)});
  EXPECT_TRUE(overlay.Predicted(CellIndex(grid, {9.0, 3.0})));
  EXPECT_FALSE(overlay.Predicted(CellIndex(grid, {11.2, 5.7}))) << "an observed pillar stays";
  EXPECT_FALSE(overlay.Predicted(CellIndex(grid, {3.0, 3.0})))
      << "observed free space is no prediction";
  EXPECT_EQ(overlay.ObjectAt(CellIndex(grid, {7.1, 4.0})), std::optional<uint32_t>(42));
  EXPECT_EQ(overlay.ObjectAt(CellIndex(grid, {7.1, 2.0})), std::nullopt) << "the wall is no cart";
  EXPECT_EQ(overlay.ObjectAt(CellIndex(grid, {6.9, 4.0})), std::nullopt) << "free cells stay free";

  grid::OccupancyGrid opened = grid;
  overlay.Open(&opened);
  EXPECT_EQ(opened.StateAt(180, 80), grid::CellState::kFree);  // (9.0, 4.0): predicted
  EXPECT_EQ(opened.at(142, 80), grid::kFreeValue);             // (7.1, 4.0): the cart
  EXPECT_EQ(opened.at(142, 40), grid::kOccupiedValue);         // (7.1, 2.0): the wall

  const RouteOverlay without_cart = RouteOverlay::Make(grid, {PredictedRightRoom()}, {});
  const std::vector<int64_t> differences = overlay.Differences(without_cart);
  EXPECT_EQ(differences.size(), overlay.object_cells());
  EXPECT_TRUE(
      std::binary_search(differences.begin(), differences.end(), CellIndex(grid, {7.1, 4.0})));
  EXPECT_TRUE(overlay.Differences(overlay).empty());
}

TEST(RouteOverlayTest, EdgesIntoAPredictedRoomExistAndAreMarkedPredicted) {
  const grid::OccupancyGrid grid = RightRoomUnseen();
  const RouteOverlay overlay = RouteOverlay::Make(grid, {PredictedRightRoom()}, {});
  ASSERT_GT(overlay.predicted_cells(), 10000U);

  RouteGraphBuilder plain(RouteGraphOptions{});
  const StatusOr<RouteGraph> observed = plain.Build(grid);
  ASSERT_TRUE(observed.ok());
  for (const RouteNode& node : observed->nodes) {
    EXPECT_LT(node.position.x(), 7.6) << "unknown space is never traversable";
  }

  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> graph = builder.Build(grid, {.overlay = &overlay});
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(Connected(*graph, 6.0, 8.5)) << "from the left room into the predicted one";
  int predicted_edges = 0;
  for (const RouteEdge& edge : graph->edges) {
    const Point2 a = graph->FindNode(edge.start)->position;
    const Point2 b = graph->FindNode(edge.end)->position;
    if (std::max(a.x(), b.x()) > 7.3) {
      EXPECT_TRUE(edge.predicted) << "edge " << edge.id << " reaches into the unseen room";
    }
    if (std::max(a.x(), b.x()) < 6.9) {
      EXPECT_FALSE(edge.predicted) << "edge " << edge.id << " lies in the observed room";
    }
    EXPECT_FALSE(edge.blocking_object);
    predicted_edges += edge.predicted ? 1 : 0;
  }
  EXPECT_GE(predicted_edges, 1);
  for (const RouteNode& node : graph->nodes) {
    EXPECT_EQ(node.predicted, node.position.x() > 7.2) << "node " << node.id;
  }
}

TEST(RouteOverlayTest, ARoomPredictedBehindAShutDoorIsReachedThroughTheDoor) {
  grid::OccupancyGrid grid = RightRoomUnseen();
  Fill(&grid, 7.0, 3.5, 7.2, 4.5, grid::kOccupiedValue);  // the door, seen shut
  PredictedSpace behind = PredictedRightRoom();
  RouteGraphBuilder without_door(RouteGraphOptions{});
  const RouteOverlay room_only = RouteOverlay::Make(grid, {behind}, {});
  const StatusOr<RouteGraph> apart = without_door.Build(grid, {.overlay = &room_only});
  ASSERT_TRUE(apart.ok());
  EXPECT_FALSE(Connected(*apart, 6.0, 8.5)) << "a shut door is a wall until it is known as a door";

  behind.door = std::array<Point2, 2>{Point2(7.1, 3.5), Point2(7.1, 4.5)};
  const RouteOverlay overlay = RouteOverlay::Make(grid, {behind}, {});
  EXPECT_TRUE(overlay.Predicted(CellIndex(grid, {7.1, 4.0})));
  EXPECT_FALSE(overlay.Predicted(CellIndex(grid, {7.1, 3.2}))) << "the jamb beside the door stays";
  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> graph = builder.Build(grid, {.overlay = &overlay});
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(Connected(*graph, 6.0, 8.5));
  for (const RouteEdge& edge : graph->edges) {
    const Point2 a = graph->FindNode(edge.start)->position;
    const Point2 b = graph->FindNode(edge.end)->position;
    if (std::max(a.x(), b.x()) > 7.0) {
      EXPECT_TRUE(edge.predicted) << "edge " << edge.id << " goes through the door or beyond";
    }
  }
}

TEST(RouteOverlayTest, AnObjectInTheDoorBlocksOnlyTheEdgesThroughItAndNamesIt) {
  grid::OccupancyGrid grid = TwoRooms(1.0);
  Fill(&grid, 7.0, 3.5, 7.2, 4.5, grid::kOccupiedValue);
  RouteGraphBuilder plain(RouteGraphOptions{});
  const StatusOr<RouteGraph> shut = plain.Build(grid);
  ASSERT_TRUE(shut.ok());
  EXPECT_FALSE(Connected(*shut, 6.0, 8.0));
  EXPECT_THAT(shut->message, ::testing::HasSubstr("parts"));

  const RouteOverlay overlay = RouteOverlay::Make(grid, {}, {CartInTheDoor(42)});
  RouteGraphBuilder builder(RouteGraphOptions{});
  const StatusOr<RouteGraph> graph = builder.Build(grid, {.overlay = &overlay});
  ASSERT_TRUE(graph.ok()) << graph.status();
  EXPECT_TRUE(Connected(*graph, 6.0, 8.0)) << "planned through the cart, marked";
  int blocked = 0;
  for (const RouteEdge& edge : graph->edges) {
    const Point2 a = graph->FindNode(edge.start)->position;
    const Point2 b = graph->FindNode(edge.end)->position;
    const bool crosses_door = std::max(a.x(), b.x()) > 7.0 && std::min(a.x(), b.x()) < 7.2;
    EXPECT_EQ(edge.blocking_object.has_value(), crosses_door) << "edge " << edge.id;
    if (edge.blocking_object) {
      EXPECT_EQ(*edge.blocking_object, 42U);
      ++blocked;
    }
    EXPECT_FALSE(edge.predicted);
  }
  EXPECT_GE(blocked, 1);

  // The exports say it: nav2's metadata and the RMF lane's properties.
  const nlohmann::json geojson = Nav2RouteGeoJson(*graph);
  int exported_blocked = 0;
  for (const nlohmann::json& feature : geojson["features"]) {
    const nlohmann::json& metadata = feature["properties"]["metadata"];
    if (metadata.contains("blocked_by_object")) {
      EXPECT_EQ(metadata["blocked_by_object"], 42);
      ++exported_blocked;
    }
  }
  EXPECT_EQ(exported_blocked, 2 * blocked) << "each edge both ways";
  const YAML::Node rmf = YAML::Load(RmfNavGraphYaml(*graph));
  int rmf_blocked = 0;
  for (const YAML::Node& lane : rmf["levels"]["L1"]["lanes"]) {
    if (lane[2]["fleetmap_blocked_by_object"]) {
      EXPECT_EQ(lane[2]["fleetmap_blocked_by_object"].as<uint32_t>(), 42U);
      ++rmf_blocked;
    }
  }
  EXPECT_EQ(rmf_blocked, 2 * blocked);
}

TEST(RouteOverlayTest, AnUpdateFollowsTheOverlayAsItComesAndGoes) {
  const grid::OccupancyGrid grid = RightRoomUnseen();
  RouteGraphBuilder builder(RouteGraphOptions{});
  ASSERT_TRUE(builder.Build(grid).ok());

  const RouteOverlay overlay = RouteOverlay::Make(grid, {PredictedRightRoom()}, {});
  const StatusOr<RouteGraph> predicted = builder.Update(grid, {}, {.overlay = &overlay});
  ASSERT_TRUE(predicted.ok()) << predicted.status();
  EXPECT_TRUE(Connected(*predicted, 6.0, 8.5));
  EXPECT_TRUE(std::any_of(predicted->edges.begin(), predicted->edges.end(),
                          [](const RouteEdge& edge) { return edge.predicted; }));

  // The same overlay again: nothing to do, the same graph.
  const StatusOr<RouteGraph> again = builder.Update(grid, {}, {.overlay = &overlay});
  ASSERT_TRUE(again.ok());
  ASSERT_EQ(again->edges.size(), predicted->edges.size());
  for (size_t i = 0; i < again->edges.size(); ++i) {
    EXPECT_EQ(again->edges[i].id, predicted->edges[i].id);
    EXPECT_EQ(again->edges[i].predicted, predicted->edges[i].predicted);
  }

  // The prediction withdrawn: the graph of the observed map again, no edge marked.
  const StatusOr<RouteGraph> withdrawn = builder.Update(grid, {});
  ASSERT_TRUE(withdrawn.ok());
  EXPECT_FALSE(Connected(*withdrawn, 6.0, 8.5));
  EXPECT_TRUE(std::none_of(withdrawn->edges.begin(), withdrawn->edges.end(),
                           [](const RouteEdge& edge) { return edge.predicted; }));
  for (const RouteNode& node : withdrawn->nodes) {
    EXPECT_LT(node.position.x(), 7.3) << "node " << node.id << " left in the unseen room";
    EXPECT_FALSE(node.predicted);
  }
}

}  // namespace
}  // namespace fleetmap::route_graph
