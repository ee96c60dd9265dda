#pragma once

// Plans on a route graph as a fleet manager does: shortest routes by edge length (Dijkstra), the
// parts of the graph, and the node a robot standing somewhere drives to first. The checks and the
// benchmark plan with it against the grid planner (grid_planner.hpp).
//
// Thread-safety: const methods may be called from any number of threads; the planner refers to
// the graph it was made with, which must outlive it.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/types.hpp"
#include "common/route_graph/clearance_map.hpp"
#include "common/route_graph/route_graph.hpp"

namespace fleetmap::route_graph {

struct Route {
  std::vector<uint32_t> nodes;  // ids, from the start to the goal
  double length = 0.0;          // metres
};

class RoutePlanner {
 public:
  explicit RoutePlanner(const RouteGraph& graph);

  // The shortest route between two node ids, or nothing when they are not connected (or unknown).
  std::optional<Route> Plan(uint32_t from, uint32_t to) const;
  // Whether two node ids are in one part of the graph.
  bool Connected(uint32_t from, uint32_t to) const;
  // The node nearest to `point` that a robot there reaches on a straight segment keeping
  // `required` on `clearance`, among the `tries` nearest nodes; nothing if none does.
  std::optional<uint32_t> Entry(const Point2& point, const ClearanceMap& clearance, double required,
                                int tries = 16) const;
  // Up to `count` such nodes, nearest first: where a planner may join the graph.
  std::vector<uint32_t> Entries(const Point2& point, const ClearanceMap& clearance, double required,
                                int tries = 16, int count = 4) const;
  // The shortest way from `from` to `to` through the graph: a straight leg to one of the entries
  // of `from`, a route, a straight leg from one of the entries of `to`; nothing if none connects.
  std::optional<double> ShortestWay(const Point2& from, const Point2& to,
                                    const ClearanceMap& clearance, double required) const;

 private:
  const RouteGraph& graph_;
  // Per node index: (neighbour index, length).
  std::vector<std::vector<std::pair<size_t, double>>> adjacency_;
  std::vector<size_t> component_;
};

}  // namespace fleetmap::route_graph
