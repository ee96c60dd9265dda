#pragma once

// The route graph builder's stages on the skeleton's cells (private to common/route_graph): the
// skeleton as a graph of curves between nodes, its spurs pruned and near junctions merged. Cells
// are linear indices y * width + x.

#include <cstdint>
#include <vector>

#include "common/route_graph/clearance_map.hpp"
#include "common/route_graph/route_graph.hpp"
#include "common/route_graph/skeleton.hpp"

namespace fleetmap::route_graph::internal {

struct SkeletonNode {
  int cell = 0;
  RouteNodeKind kind = RouteNodeKind::kJunction;
  bool alive = true;
};

// A curve of skeleton cells from node `from`'s cell to node `to`'s cell, both included.
struct SkeletonBranch {
  int from = 0;
  int to = 0;
  std::vector<int> cells;
  bool alive = true;
};

struct SkeletonGraph {
  int width = 0;
  std::vector<SkeletonNode> nodes;
  std::vector<SkeletonBranch> branches;
};

// Nodes where curves end (dead ends), meet (junctions: a cluster of touching junction cells is one
// node, at its cell of most clearance) or would have none (one node on each closed loop).
SkeletonGraph TraceSkeleton(const Skeleton& skeleton, const ClearanceMap& clearance);

// Removes dead-end branches shorter than `min_spur_length` plus how much further the junction is
// from the walls than the end (a wall's bump, not a corridor), and joins the two branches of a
// node left with two.
void PruneSpurs(const ClearanceMap& clearance, double min_spur_length, SkeletonGraph* graph);

// Contracts branches shorter than `merge_distance` between two junctions into the junction with
// more clearance (one crossing, not two).
void MergeNearJunctions(const ClearanceMap& clearance, double merge_distance, SkeletonGraph* graph);

// The length of a branch's curve, metres.
double BranchLength(const SkeletonBranch& branch, int width, double resolution);

}  // namespace fleetmap::route_graph::internal
