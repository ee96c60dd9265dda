#include "common/route_graph/route_graph.hpp"

#include <algorithm>

namespace fleetmap::route_graph {

std::string_view RouteNodeKindName(RouteNodeKind kind) {
  switch (kind) {
    case RouteNodeKind::kJunction:
      return "junction";
    case RouteNodeKind::kDeadEnd:
      return "dead_end";
    case RouteNodeKind::kDoorway:
      return "doorway";
    case RouteNodeKind::kRoomCentre:
      return "room_centre";
    case RouteNodeKind::kLane:
      return "lane";
  }
  return "lane";
}

std::optional<size_t> RouteGraph::NodeIndex(uint32_t id) const {
  const auto it =
      std::lower_bound(nodes.begin(), nodes.end(), id,
                       [](const RouteNode& node, uint32_t key) { return node.id < key; });
  if (it == nodes.end() || it->id != id) return std::nullopt;
  return static_cast<size_t>(it - nodes.begin());
}

const RouteNode* RouteGraph::FindNode(uint32_t id) const {
  const std::optional<size_t> index = NodeIndex(id);
  return index ? &nodes[*index] : nullptr;
}

}  // namespace fleetmap::route_graph
