#include "common/route_graph/route_planner.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

namespace fleetmap::route_graph {

RoutePlanner::RoutePlanner(const RouteGraph& graph)
    : graph_(graph), adjacency_(graph.nodes.size()), component_(graph.nodes.size()) {
  for (const RouteEdge& edge : graph.edges) {
    const std::optional<size_t> a = graph.NodeIndex(edge.start);
    const std::optional<size_t> b = graph.NodeIndex(edge.end);
    if (!a || !b) continue;
    adjacency_[*a].push_back({*b, edge.length});
    adjacency_[*b].push_back({*a, edge.length});
  }
  constexpr size_t kNone = std::numeric_limits<size_t>::max();
  std::fill(component_.begin(), component_.end(), kNone);
  std::vector<size_t> stack;
  for (size_t start = 0; start < graph.nodes.size(); ++start) {
    if (component_[start] != kNone) continue;
    component_[start] = start;
    stack.push_back(start);
    while (!stack.empty()) {
      const size_t node = stack.back();
      stack.pop_back();
      for (const auto& [next, length] : adjacency_[node]) {
        if (component_[next] != kNone) continue;
        component_[next] = start;
        stack.push_back(next);
      }
    }
  }
}

bool RoutePlanner::Connected(uint32_t from, uint32_t to) const {
  const std::optional<size_t> a = graph_.NodeIndex(from);
  const std::optional<size_t> b = graph_.NodeIndex(to);
  return a && b && component_[*a] == component_[*b];
}

std::optional<Route> RoutePlanner::Plan(uint32_t from, uint32_t to) const {
  const std::optional<size_t> start = graph_.NodeIndex(from);
  const std::optional<size_t> goal = graph_.NodeIndex(to);
  if (!start || !goal || component_[*start] != component_[*goal]) return std::nullopt;
  const double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<double> distance(graph_.nodes.size(), kInfinity);
  std::vector<size_t> parent(graph_.nodes.size(), *start);
  using Entry = std::pair<double, size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  distance[*start] = 0.0;
  open.push({0.0, *start});
  while (!open.empty()) {
    const auto [d, node] = open.top();
    open.pop();
    if (d > distance[node]) continue;
    if (node == *goal) break;
    for (const auto& [next, length] : adjacency_[node]) {
      if (d + length >= distance[next]) continue;
      distance[next] = d + length;
      parent[next] = node;
      open.push({distance[next], next});
    }
  }
  Route route;
  route.length = distance[*goal];
  for (size_t node = *goal;; node = parent[node]) {
    route.nodes.push_back(graph_.nodes[node].id);
    if (node == *start) break;
  }
  std::reverse(route.nodes.begin(), route.nodes.end());
  return route;
}

std::vector<uint32_t> RoutePlanner::Entries(const Point2& point, const ClearanceMap& clearance,
                                            double required, int tries, int count) const {
  std::vector<std::pair<double, size_t>> nearest;
  nearest.reserve(graph_.nodes.size());
  for (size_t i = 0; i < graph_.nodes.size(); ++i) {
    nearest.push_back({(graph_.nodes[i].position - point).squaredNorm(), i});
  }
  const size_t considered = std::min(nearest.size(), static_cast<size_t>(std::max(tries, 0)));
  std::partial_sort(nearest.begin(), nearest.begin() + considered, nearest.end());
  std::vector<uint32_t> entries;
  for (size_t k = 0; k < considered && static_cast<int>(entries.size()) < count; ++k) {
    const RouteNode& node = graph_.nodes[nearest[k].second];
    if (clearance.SegmentKeeps(point, node.position, required)) entries.push_back(node.id);
  }
  return entries;
}

std::optional<uint32_t> RoutePlanner::Entry(const Point2& point, const ClearanceMap& clearance,
                                            double required, int tries) const {
  const std::vector<uint32_t> entries = Entries(point, clearance, required, tries, 1);
  if (entries.empty()) return std::nullopt;
  return entries.front();
}

std::optional<double> RoutePlanner::ShortestWay(const Point2& from, const Point2& to,
                                                const ClearanceMap& clearance,
                                                double required) const {
  const std::vector<uint32_t> starts = Entries(from, clearance, required);
  const std::vector<uint32_t> goals = Entries(to, clearance, required);
  std::optional<double> best;
  for (const uint32_t start : starts) {
    for (const uint32_t goal : goals) {
      const std::optional<Route> route = Plan(start, goal);
      if (!route) continue;
      const double length = (graph_.FindNode(start)->position - from).norm() + route->length +
                            (graph_.FindNode(goal)->position - to).norm();
      if (!best || length < *best) best = length;
    }
  }
  return best;
}

}  // namespace fleetmap::route_graph
