#pragma once

// One node of the fleet's sub-map graph as the server publishes it (rt/fleetmap/submap_graph):
// the sub-map, where it stands (observed, predicted, confirmed, retracted), what made it, how
// right it turned out, and the edges that start from it. Plain data shared by the prediction
// tracker (common/extrapolation) and the DDS edge (transport::SubmapMessage).

#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::scene {

// In the fleet frame. An observed place's `submap.navigable` holds the place's cells: free, or
// extrapolation::kConditionallyFree where only people's tracks make them free.
struct SubmapNode {
  Submap submap;
  SubmapState state = SubmapState::kPredicted;
  RobotId source_robot;
  std::string source_entity;
  float precision = -1.0F;  // measured against later observation; -1 before any
  float observed_fraction = -1.0F;
  std::vector<SubmapEdge> edges;  // each edge's `from` is this sub-map
  Timestamp stamp{};
};

}  // namespace fleetmap::scene
