#include "common/route_graph/internal/skeleton_graph.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "common/core/check.hpp"

namespace fleetmap::route_graph::internal {
namespace {

constexpr std::array<int, 8> kRingX = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr std::array<int, 8> kRingY = {0, 1, 1, 1, 0, -1, -1, -1};

// The number of skeleton cells around a cell: 2 on a curve, 1 at its end, 0 alone. Where curves
// meet, several touching cells have 3 or more (they become one node); a cell of 3 that only
// thickens a curve makes a node of two branches, which PruneSpurs dissolves.
int NeighbourCount(const Skeleton& skeleton, int x, int y) {
  int count = 0;
  for (int k = 0; k < 8; ++k) count += skeleton.at(x + kRingX[k], y + kRingY[k]) ? 1 : 0;
  return count;
}

// Calls visit(n, k) for each skeleton cell n around `cell` (row-major on `width`), k its place in
// the ring (even: a straight step).
template <typename Visit>
void ForEachSkeletonNeighbour(const Skeleton& skeleton, int cell, int width, Visit&& visit) {
  const int cx = cell % width;
  const int cy = cell / width;
  for (int k = 0; k < 8; ++k) {
    const int nx = cx + kRingX[k];
    const int ny = cy + kRingY[k];
    if (skeleton.at(nx, ny)) visit(ny * width + nx, k);
  }
}

double StepLength(int a, int b, int width) {
  const int dx = std::abs(a % width - b % width);
  const int dy = std::abs(a / width - b / width);
  return (dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0;
}

std::vector<int> NodeDegrees(const SkeletonGraph& graph) {
  std::vector<int> degree(graph.nodes.size(), 0);
  for (const SkeletonBranch& branch : graph.branches) {
    if (!branch.alive) continue;
    ++degree[branch.from];
    ++degree[branch.to];
  }
  return degree;
}

// The branch's cells ordered to start at node `node` (one of its ends).
std::vector<int> CellsFrom(const SkeletonBranch& branch, int node) {
  std::vector<int> cells = branch.cells;
  if (branch.from != node) std::reverse(cells.begin(), cells.end());
  return cells;
}

// Joins the two branches of every node with exactly two (not a loop's own node on its loop).
void DissolveDegreeTwo(SkeletonGraph* graph) {
  std::vector<std::vector<int>> incident(graph->nodes.size());
  for (size_t b = 0; b < graph->branches.size(); ++b) {
    const SkeletonBranch& branch = graph->branches[b];
    if (!branch.alive) continue;
    incident[branch.from].push_back(static_cast<int>(b));
    if (branch.to != branch.from) incident[branch.to].push_back(static_cast<int>(b));
  }
  for (size_t n = 0; n < graph->nodes.size(); ++n) {
    SkeletonNode& node = graph->nodes[n];
    if (!node.alive || node.kind == RouteNodeKind::kLane) continue;
    std::vector<int>& list = incident[n];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [graph](int b) { return !graph->branches[b].alive; }),
               list.end());
    if (list.size() != 2) continue;
    SkeletonBranch& first = graph->branches[list[0]];
    SkeletonBranch& second = graph->branches[list[1]];
    if (first.from == first.to || second.from == second.to) continue;
    const int node_index = static_cast<int>(n);
    const int a = first.from == node_index ? first.to : first.from;
    const int c = second.from == node_index ? second.to : second.from;
    std::vector<int> cells = CellsFrom(first, a);
    const std::vector<int> rest = CellsFrom(second, node_index);
    cells.insert(cells.end(), rest.begin() + 1, rest.end());
    first.from = a;
    first.to = c;
    first.cells = std::move(cells);
    second.alive = false;
    node.alive = false;
    // The joined branch now also ends at c: keep c's list pointing at it.
    std::replace(incident[c].begin(), incident[c].end(), list[1], list[0]);
  }
}

}  // namespace

double BranchLength(const SkeletonBranch& branch, int width, double resolution) {
  double cells = 0.0;
  for (size_t i = 1; i < branch.cells.size(); ++i) {
    cells += StepLength(branch.cells[i - 1], branch.cells[i], width);
  }
  return cells * resolution;
}

SkeletonGraph TraceSkeleton(const Skeleton& skeleton, const ClearanceMap& clearance) {
  const int width = skeleton.width();
  SkeletonGraph graph;
  graph.width = width;
  std::vector<int> cells;
  for (int y = 0; y < skeleton.height(); ++y) {
    for (int x = 0; x < width; ++x) {
      if (skeleton.at(x, y)) cells.push_back(y * width + x);
    }
  }
  // Per skeleton cell: its node (-1 for a curve cell) and whether a branch went through it.
  std::unordered_map<int, int> node_of;
  node_of.reserve(cells.size() / 4 + 16);
  std::unordered_set<int> visited;
  visited.reserve(cells.size() * 2);
  std::unordered_map<int, int> groups;  // neighbour counts
  groups.reserve(cells.size() * 2);
  for (const int cell : cells) {
    groups[cell] = NeighbourCount(skeleton, cell % width, cell / width);
  }
  auto is_node_cell = [&groups](int cell) { return groups.at(cell) != 2; };

  // Clusters of touching node cells become one node.
  std::vector<std::vector<int>> members;
  std::unordered_map<int, int> toward_node;  // node cell -> the next cell towards its node's cell
  // The cells from a node cell to its node's cell, both included.
  auto to_node_cell = [&toward_node](int cell) {
    std::vector<int> path = {cell};
    const auto found = toward_node.find(cell);
    if (found == toward_node.end()) return path;
    while (toward_node.at(path.back()) != path.back()) path.push_back(toward_node.at(path.back()));
    return path;
  };
  // A traced branch, its ends extended to its nodes' cells.
  auto finish = [&](SkeletonBranch branch) {
    std::vector<int> head = to_node_cell(branch.cells.front());
    std::reverse(head.begin(), head.end());
    const std::vector<int> tail = to_node_cell(branch.cells.back());
    std::vector<int> cells = std::move(head);
    cells.insert(cells.end(), branch.cells.begin() + 1, branch.cells.end());
    cells.insert(cells.end(), tail.begin() + 1, tail.end());
    branch.cells = std::move(cells);
    graph.branches.push_back(std::move(branch));
  };
  for (const int cell : cells) {
    if (!is_node_cell(cell) || node_of.count(cell) != 0) continue;
    const int node = static_cast<int>(graph.nodes.size());
    std::vector<int> cluster = {cell};
    node_of[cell] = node;
    for (size_t i = 0; i < cluster.size(); ++i) {
      ForEachSkeletonNeighbour(skeleton, cluster[i], width, [&](int n, int /*k*/) {
        if (!is_node_cell(n) || node_of.count(n) != 0) return;
        node_of[n] = node;
        cluster.push_back(n);
      });
    }
    int best = cluster.front();
    for (const int member : cluster) {
      const float value = clearance.at(member % width, member / width);
      const float best_value = clearance.at(best % width, best / width);
      if (value > best_value || (value == best_value && member < best)) best = member;
    }
    const int group_count = groups.at(cluster.front());
    const RouteNodeKind kind = (cluster.size() == 1 && group_count <= 1) ? RouteNodeKind::kDeadEnd
                                                                         : RouteNodeKind::kJunction;
    graph.nodes.push_back({best, kind, true});
    // Paths inside the cluster from its node's cell, so branches start and end on that cell.
    toward_node[best] = best;
    std::vector<int> frontier = {best};
    for (size_t i = 0; i < frontier.size(); ++i) {
      ForEachSkeletonNeighbour(skeleton, frontier[i], width, [&](int n, int /*k*/) {
        const auto member = node_of.find(n);
        if (member == node_of.end() || member->second != node || toward_node.count(n) != 0) {
          return;
        }
        toward_node[n] = frontier[i];
        frontier.push_back(n);
      });
    }
    members.push_back(std::move(cluster));
  }

  auto trace = [&](int node, int start, int first) {
    SkeletonBranch branch;
    branch.from = node;
    branch.cells = {start, first};
    const auto first_node = node_of.find(first);
    if (first_node != node_of.end()) {
      branch.to = first_node->second;
      finish(std::move(branch));
      return;
    }
    visited.insert(first);
    int previous = start;
    int current = first;
    while (true) {
      int next_node_cell = -1;  // of another node (or of the start node, closing a loop)
      bool next_node_other = false;
      int next_cell = -1;
      bool next_straight = false;
      ForEachSkeletonNeighbour(skeleton, current, width, [&](int n, int k) {
        if (n == previous) return;
        const auto found = node_of.find(n);
        if (found != node_of.end()) {
          const bool other = found->second != node;
          // Leaving the start node: its other cells are not where this curve goes.
          if (!other && branch.cells.size() < 3) return;
          if (next_node_cell < 0 || (other && !next_node_other)) {
            next_node_cell = n;
            next_node_other = other;
          }
          return;
        }
        if (visited.count(n) != 0) return;
        const bool straight = k % 2 == 0;
        if (next_cell < 0 || (straight && !next_straight)) {
          next_cell = n;
          next_straight = straight;
        }
      });
      // Back to the start node only when the curve goes nowhere else.
      if (next_node_cell >= 0 && !next_node_other && next_cell >= 0) next_node_cell = -1;
      if (next_node_cell >= 0) {
        branch.cells.push_back(next_node_cell);
        branch.to = node_of.at(next_node_cell);
        break;
      }
      if (next_cell < 0) {
        // A curve that stops without an end cell (left over by an earlier trace): end it here.
        const int end = static_cast<int>(graph.nodes.size());
        graph.nodes.push_back({current, RouteNodeKind::kDeadEnd, true});
        node_of[current] = end;
        branch.to = end;
        break;
      }
      visited.insert(next_cell);
      branch.cells.push_back(next_cell);
      previous = current;
      current = next_cell;
    }
    finish(std::move(branch));
  };

  std::unordered_set<int64_t> direct_pairs;
  for (size_t node = 0; node < members.size(); ++node) {
    for (const int cell : members[node]) {
      ForEachSkeletonNeighbour(skeleton, cell, width, [&](int n, int /*k*/) {
        const auto found = node_of.find(n);
        if (found != node_of.end()) {
          if (found->second == static_cast<int>(node)) return;
          const int64_t lo = std::min<int64_t>(found->second, static_cast<int64_t>(node));
          const int64_t hi = std::max<int64_t>(found->second, static_cast<int64_t>(node));
          if (!direct_pairs.insert(lo * (int64_t{1} << 32) + hi).second) return;
          trace(static_cast<int>(node), cell, n);
          return;
        }
        if (visited.count(n) != 0) return;
        trace(static_cast<int>(node), cell, n);
      });
    }
  }
  // Closed loops with no node on them: one node each, traced round to itself.
  for (const int cell : cells) {
    if (node_of.count(cell) != 0 || visited.count(cell) != 0) continue;
    const int node = static_cast<int>(graph.nodes.size());
    graph.nodes.push_back({cell, RouteNodeKind::kLane, true});
    node_of[cell] = node;
    ForEachSkeletonNeighbour(skeleton, cell, width, [&](int n, int /*k*/) {
      if (visited.count(n) != 0 || node_of.count(n) != 0) return;
      trace(node, cell, n);
    });
  }
  return graph;
}

void PruneSpurs(const ClearanceMap& clearance, double min_spur_length, SkeletonGraph* graph) {
  const int width = graph->width;
  auto clearance_of = [&](int node) {
    const int cell = graph->nodes[node].cell;
    return static_cast<double>(clearance.at(cell % width, cell / width));
  };
  for (int round = 0; round < 8; ++round) {
    const std::vector<int> degree = NodeDegrees(*graph);
    bool pruned = false;
    for (SkeletonBranch& branch : graph->branches) {
      if (!branch.alive || branch.from == branch.to) continue;
      int end = -1;
      int junction = -1;
      if (degree[branch.from] == 1 && degree[branch.to] >= 3) {
        end = branch.from;
        junction = branch.to;
      } else if (degree[branch.to] == 1 && degree[branch.from] >= 3) {
        end = branch.to;
        junction = branch.from;
      } else {
        continue;
      }
      const double allowed =
          min_spur_length + std::max(0.0, clearance_of(junction) - clearance_of(end));
      if (BranchLength(branch, width, clearance.resolution()) >= allowed) continue;
      branch.alive = false;
      graph->nodes[end].alive = false;
      pruned = true;
    }
    DissolveDegreeTwo(graph);
    if (!pruned) break;
  }
}

void MergeNearJunctions(const ClearanceMap& clearance, double merge_distance,
                        SkeletonGraph* graph) {
  const int width = graph->width;
  auto clearance_of = [&](int node) {
    const int cell = graph->nodes[node].cell;
    return clearance.at(cell % width, cell / width);
  };
  std::vector<int> degree = NodeDegrees(*graph);
  for (size_t b = 0; b < graph->branches.size(); ++b) {
    SkeletonBranch& branch = graph->branches[b];
    if (!branch.alive || branch.from == branch.to) continue;
    if (degree[branch.from] < 3 || degree[branch.to] < 3) continue;
    if (BranchLength(branch, width, clearance.resolution()) >= merge_distance) continue;
    const bool keep_from = clearance_of(branch.from) >= clearance_of(branch.to);
    const int keep = keep_from ? branch.from : branch.to;
    const int gone = keep_from ? branch.to : branch.from;
    const std::vector<int> bridge = CellsFrom(branch, keep);  // keep ... gone
    branch.alive = false;
    for (SkeletonBranch& other : graph->branches) {
      if (!other.alive) continue;
      if (other.from != gone && other.to != gone) continue;
      if (other.from == gone && other.to == gone) {
        std::vector<int> cells = bridge;
        cells.insert(cells.end(), other.cells.begin() + 1, other.cells.end());
        cells.insert(cells.end(), bridge.rbegin() + 1, bridge.rend());
        other.cells = std::move(cells);
        other.from = keep;
        other.to = keep;
        continue;
      }
      const int far = other.from == gone ? other.to : other.from;
      std::vector<int> cells = bridge;
      const std::vector<int> rest = CellsFrom(other, gone);
      cells.insert(cells.end(), rest.begin() + 1, rest.end());
      other.cells = std::move(cells);
      other.from = keep;
      other.to = far;
    }
    graph->nodes[gone].alive = false;
    degree[keep] += degree[gone] - 2;
    degree[gone] = 0;
  }
  DissolveDegreeTwo(graph);
}

}  // namespace fleetmap::route_graph::internal
