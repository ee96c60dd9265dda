#pragma once

// The fleet map as a route graph (issue 37): a sparse graph of places a robot of a given radius
// can reach (room centres, doorways, corridor junctions, dead ends, lane nodes along long
// corridors) joined by straight edges on which it fits with a clearance margin. Plain data in the
// map frame; RouteGraphBuilder makes it, the exports (route_graph_export.hpp) write it for nav2's
// route server and Open-RMF. docs/route-graph.md describes the method.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::route_graph {

enum class RouteNodeKind : uint8_t {
  kJunction,    // where three or more corridors meet (a room's middle is one too)
  kDeadEnd,     // where a corridor ends
  kDoorway,     // the narrowest point of a passage between two wider spaces
  kRoomCentre,  // the middle of a room of the sub-map graph
  kLane,        // on a corridor: a bend, a tile border, or a lane node every `lane_spacing`
};

// "junction", "dead_end", "doorway", "room_centre", "lane".
std::string_view RouteNodeKindName(RouteNodeKind kind);

// Ids are unique across nodes and edges (nav2_route requires it) and stable: a node or edge whose
// geometry did not change between two builds keeps its id.
struct RouteNode {
  uint32_t id = 0;
  Point2 position = Point2::Zero();  // map frame, metres
  RouteNodeKind kind = RouteNodeKind::kLane;
  double clearance = 0.0;  // metres from the node to the nearest non-free cell (capped)
  // The node stands on free space the server predicts and no robot has observed yet.
  bool predicted = false;
};

// An undirected straight edge. `id` names it from `start` to `end`, `reverse_id` from `end` to
// `start` (the two directed edges of the nav2 export).
struct RouteEdge {
  uint32_t id = 0;
  uint32_t reverse_id = 0;
  uint32_t start = 0;  // node ids
  uint32_t end = 0;
  double length = 0.0;     // metres
  double clearance = 0.0;  // the narrowest clearance along the edge, metres (capped)
  // The edge crosses free space the server predicts and no robot has observed yet: a robot
  // sent along it confirms the prediction (or finds the way shut) on the way.
  bool predicted = false;
  // The learned movable object (rt/fleetmap/objects id) the edge runs through: the way is there
  // once the object is moved. Clearances are measured as if it were gone.
  std::optional<uint32_t> blocking_object;
};

struct RouteGraph {
  std::string frame = "map";
  double robot_radius = 0.0;  // what the graph was built for
  double clearance_margin = 0.0;
  std::vector<RouteNode> nodes;  // sorted by id
  std::vector<RouteEdge> edges;  // sorted by id
  // Why the graph is empty or in parts that do not connect (for the user); empty when neither.
  std::string message;

  // The node with this id, or nullptr.
  const RouteNode* FindNode(uint32_t id) const;
  // The index in `nodes` of each node id, for graph searches: nodes are sorted by id.
  std::optional<size_t> NodeIndex(uint32_t id) const;
};

}  // namespace fleetmap::route_graph
