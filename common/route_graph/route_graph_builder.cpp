#include "common/route_graph/route_graph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "common/core/check.hpp"
#include "common/core/number_format.hpp"
#include "common/route_graph/internal/skeleton_graph.hpp"
#include "common/route_graph/segment_memo.hpp"

namespace fleetmap::route_graph {
namespace {

using internal::SkeletonBranch;
using internal::SkeletonGraph;

bool PositiveFinite(double value) { return std::isfinite(value) && value > 0.0; }

// Positions are matched across builds at a tenth of a millimetre.
using PositionKey = std::pair<int64_t, int64_t>;
PositionKey KeyOf(const Point2& point) {
  return {static_cast<int64_t>(std::llround(point.x() * 1e4)),
          static_cast<int64_t>(std::llround(point.y() * 1e4))};
}

// How specific a node's kind is: when two stages place a node at one spot, the more specific wins.
int KindRank(RouteNodeKind kind) {
  switch (kind) {
    case RouteNodeKind::kRoomCentre:
      return 4;
    case RouteNodeKind::kDoorway:
      return 3;
    case RouteNodeKind::kJunction:
    case RouteNodeKind::kDeadEnd:
      return 2;
    case RouteNodeKind::kLane:
      return 1;
  }
  return 0;
}

grid::CellRect Dilate(const grid::CellRect& rect, int cells) {
  return {rect.x0 - cells, rect.y0 - cells, rect.width + 2 * cells, rect.height + 2 * cells};
}

// `grid` with the overlay's cells free, or nothing when the overlay is empty (the caller then
// builds on `grid` itself, without a copy).
grid::OccupancyGrid OpenedGrid(const grid::OccupancyGrid& grid, const RouteOverlay& overlay) {
  if (overlay.empty()) return {};
  grid::OccupancyGrid opened = grid;
  overlay.Open(&opened);
  return opened;
}

// The blocks (`block` cells square, aligned to the grid) holding any of `cells` (indices of a
// grid `width` x `height`), one rectangle each.
std::vector<grid::CellRect> BlocksHolding(const std::vector<int64_t>& cells, int width, int height,
                                          int block) {
  std::set<std::pair<int, int>> blocks;
  for (const int64_t cell : cells) {
    blocks.insert({static_cast<int>(cell % width) / block, static_cast<int>(cell / width) / block});
  }
  std::vector<grid::CellRect> rects;
  for (const auto& [bx, by] : blocks) {
    const int x0 = bx * block;
    const int y0 = by * block;
    rects.push_back({x0, y0, std::min(block, width - x0), std::min(block, height - y0)});
  }
  return rects;
}

// The segment checks of one Extract(): the clearance map's, through the builder's memo.
class Segments {
 public:
  Segments(const ClearanceMap& clearance, SegmentMemo& memo) : clearance_(clearance), memo_(memo) {}

  bool Keeps(const Point2& a, const Point2& b, double required) {
    return memo_.Keeps(clearance_, a, b, required);
  }
  double Clearance(const Point2& a, const Point2& b) { return memo_.Clearance(clearance_, a, b); }

 private:
  const ClearanceMap& clearance_;
  SegmentMemo& memo_;
};

// The graph as it is assembled: nodes by index (deduplicated by position), undirected edges.
class Assembly {
 public:
  Assembly(Segments& segments, double lane_spacing)
      : segments_(segments), lane_spacing_(lane_spacing) {}

  int AddNode(const Point2& position, RouteNodeKind kind, double node_clearance) {
    const PositionKey key = KeyOf(position);
    const auto found = index_.find(key);
    if (found != index_.end()) {
      RouteNode& node = nodes_[found->second];
      if (KindRank(kind) > KindRank(node.kind)) node.kind = kind;
      return found->second;
    }
    RouteNode node;
    node.position = position;
    node.kind = kind;
    node.clearance = node_clearance;
    nodes_.push_back(node);
    const int index = static_cast<int>(nodes_.size()) - 1;
    index_.emplace(key, index);
    return index;
  }

  // A straight, already checked segment; cut into equal lanes no longer than the spacing.
  void AddSegment(int a, int b) {
    if (a == b) return;
    const Point2 from = nodes_[a].position;
    const Point2 to = nodes_[b].position;
    const int parts = std::max(1, static_cast<int>(std::ceil((to - from).norm() / lane_spacing_)));
    int previous = a;
    for (int k = 1; k <= parts; ++k) {
      int next = b;
      if (k < parts) {
        const Point2 point = from + (to - from) * (static_cast<double>(k) / parts);
        next = AddNode(point, RouteNodeKind::kLane, segments_.Clearance(point, point));
      }
      AddEdge(previous, next);
      previous = next;
    }
  }

  void AddEdge(int a, int b) {
    if (a == b) return;
    if (!edge_set_.insert({std::min(a, b), std::max(a, b)}).second) return;
    RouteEdge edge;
    edge.start = static_cast<uint32_t>(a);
    edge.end = static_cast<uint32_t>(b);
    edge.length = (nodes_[b].position - nodes_[a].position).norm();
    edge.clearance = segments_.Clearance(nodes_[a].position, nodes_[b].position);
    edges_.push_back(edge);
  }

  std::vector<RouteNode>& nodes() { return nodes_; }
  std::vector<RouteEdge>& edges() { return edges_; }

 private:
  Segments& segments_;
  double lane_spacing_;
  std::vector<RouteNode> nodes_;
  std::map<PositionKey, int> index_;
  std::vector<RouteEdge> edges_;  // start / end are node indices until ids are assigned
  std::set<std::pair<int, int>> edge_set_;
};

struct Cut {
  size_t index = 0;
  RouteNodeKind kind = RouteNodeKind::kLane;
};

// Where a curve is cut: at doorways (a clearance minimum well below the widest clearance on both
// sides within the window) and where it crosses a tile border.
std::vector<Cut> CutPoints(const std::vector<int>& cells, int width, const ClearanceMap& clearance,
                           const RouteGraphOptions& options) {
  const size_t n = cells.size();
  std::vector<Cut> cuts;
  if (n < 5) return cuts;
  std::vector<float> value(n);
  for (size_t i = 0; i < n; ++i) value[i] = clearance.at(cells[i] % width, cells[i] / width);
  const size_t window =
      std::max<size_t>(2, static_cast<size_t>(options.doorway_window / clearance.resolution()));
  const size_t keep_off = 2;
  for (size_t i = 1; i + 1 < n; ++i) {
    if (!(value[i] < value[i - 1])) continue;  // the start of a plateau
    size_t end = i;
    while (end + 1 < n && value[end + 1] == value[i]) ++end;
    if (end + 1 >= n) break;
    if (!(value[end + 1] > value[i])) continue;
    const size_t lo = i > window ? i - window : 0;
    const size_t hi = std::min(n - 1, end + window);
    float left = 0.0F;
    float right = 0.0F;
    bool lowest = true;
    for (size_t j = lo; j <= hi; ++j) {
      if (value[j] < value[i]) lowest = false;
      if (j < i) left = std::max(left, value[j]);
      if (j > end) right = std::max(right, value[j]);
    }
    const size_t middle = (i + end) / 2;
    if (lowest && value[i] < options.doorway_ratio * std::min(left, right) && middle >= keep_off &&
        middle + keep_off < n) {
      cuts.push_back({middle, RouteNodeKind::kDoorway});
    }
    i = end;
  }
  auto tile_of = [&](size_t i) {
    const Point2 point = clearance.CellCenter(cells[i] % width, cells[i] / width);
    return std::make_pair(static_cast<int64_t>(std::floor(point.x() / options.tile_size)),
                          static_cast<int64_t>(std::floor(point.y() / options.tile_size)));
  };
  const size_t min_gap =
      std::max<size_t>(keep_off, static_cast<size_t>(0.3 / clearance.resolution()));
  std::vector<Cut> borders;
  for (size_t i = min_gap; i + min_gap < n; ++i) {
    if (tile_of(i) == tile_of(i - 1)) continue;
    const bool near_doorway = std::any_of(cuts.begin(), cuts.end(), [&](const Cut& cut) {
      return (cut.index > i ? cut.index - i : i - cut.index) < min_gap;
    });
    if (!near_doorway) borders.push_back({i, RouteNodeKind::kLane});
  }
  cuts.insert(cuts.end(), borders.begin(), borders.end());
  std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.index < b.index; });
  return cuts;
}

// The indices of `points` in [first, last] kept as corners: each segment between two corners
// keeps `required`. Greedy: from each corner, the farthest point ahead it sees, found by doubling
// the step and then halving it (the neighbouring point is always seen: adjacent skeleton cells).
std::vector<size_t> Straighten(const std::vector<Point2>& points, size_t first, size_t last,
                               Segments& segments, double required) {
  std::vector<size_t> corners = {first};
  size_t from = first;
  auto sees = [&](size_t to) { return segments.Keeps(points[from], points[to], required); };
  while (from < last) {
    if (sees(last)) {
      corners.push_back(last);
      break;
    }
    size_t good = from + 1;
    size_t step = 1;
    size_t bad = last;
    while (good + step < last) {
      if (!sees(good + step)) {
        bad = good + step;
        break;
      }
      good += step;
      step *= 2;
    }
    while (bad > good + 1) {
      const size_t middle = good + (bad - good) / 2;
      if (sees(middle)) {
        good = middle;
      } else {
        bad = middle;
      }
    }
    corners.push_back(good);
    from = good;
  }
  return corners;
}

// Union-find over node indices, for the parts of a graph.
int CountComponents(size_t node_count, const std::vector<RouteEdge>& edges) {
  std::vector<size_t> parent(node_count);
  std::iota(parent.begin(), parent.end(), size_t{0});
  auto find = [&parent](size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const RouteEdge& edge : edges) parent[find(edge.start)] = find(edge.end);
  int components = 0;
  for (size_t i = 0; i < node_count; ++i) components += find(i) == i ? 1 : 0;
  return components;
}

// Straight edges between nodes within `radius` of each other that see each other with the edge
// clearance, where the graph's way between them is more than `ratio` times longer: across rooms
// and open space, where the skeleton goes round by the middle. Decided on the graph as it was
// before any shortcut, so the result does not depend on the order nodes are looked at.
void AddShortcuts(Segments& segments, double required, double radius, double ratio,
                  Assembly* assembly) {
  const std::vector<RouteNode>& nodes = assembly->nodes();
  std::vector<std::vector<std::pair<int, double>>> adjacency(nodes.size());
  for (const RouteEdge& edge : assembly->edges()) {
    adjacency[edge.start].push_back({static_cast<int>(edge.end), edge.length});
    adjacency[edge.end].push_back({static_cast<int>(edge.start), edge.length});
  }
  std::map<std::pair<int64_t, int64_t>, std::vector<int>> bins;
  auto bin_of = [radius](const Point2& p) {
    return std::make_pair(static_cast<int64_t>(std::floor(p.x() / radius)),
                          static_cast<int64_t>(std::floor(p.y() / radius)));
  };
  for (size_t i = 0; i < nodes.size(); ++i) bins[bin_of(nodes[i].position)].push_back(int(i));
  std::vector<std::pair<int, int>> shortcuts;
  std::map<int, double> distance;
  for (size_t i = 0; i < nodes.size(); ++i) {
    // The graph's distances from node i, as far as a shortcut could matter.
    distance.clear();
    const double bound = ratio * radius;
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    distance[int(i)] = 0.0;
    open.push({0.0, int(i)});
    while (!open.empty()) {
      const auto [d, node] = open.top();
      open.pop();
      if (d > distance[node]) continue;
      for (const auto& [next, length] : adjacency[node]) {
        const double through = d + length;
        if (through > bound) continue;
        const auto found = distance.find(next);
        if (found != distance.end() && found->second <= through) continue;
        distance[next] = through;
        open.push({through, next});
      }
    }
    const auto [bx, by] = bin_of(nodes[i].position);
    for (int64_t dy = -1; dy <= 1; ++dy) {
      for (int64_t dx = -1; dx <= 1; ++dx) {
        const auto bin = bins.find({bx + dx, by + dy});
        if (bin == bins.end()) continue;
        for (const int j : bin->second) {
          if (j <= int(i)) continue;
          const double straight = (nodes[j].position - nodes[i].position).norm();
          if (straight > radius || straight < 1e-9) continue;
          const auto found = distance.find(j);
          if (found != distance.end() && found->second <= ratio * straight) continue;
          if (!segments.Keeps(nodes[i].position, nodes[j].position, required)) continue;
          shortcuts.push_back({int(i), j});
        }
      }
    }
  }
  for (const auto& [a, b] : shortcuts) assembly->AddEdge(a, b);
}

// Merges the nodes joined by an edge shorter than `min_distance`. The node of the more specific
// kind stays (of two doorways the narrower, of two others the more open), and takes the other's
// edges when each of them, moved to it, still keeps `required` (else both stay). Shortest edges
// first, ties by position, so the result does not depend on the order of the nodes, and a merge
// looks no further than the edges it moves: an update far away changes none. Indices are
// renumbered.
void MergeCloseNodes(Segments& segments, double required, double min_distance,
                     std::vector<RouteNode>* nodes, std::vector<RouteEdge>* edges) {
  struct Candidate {
    double length;
    PositionKey first, second;
    int a, b;
  };
  std::vector<Candidate> candidates;
  std::vector<std::set<int>> neighbours(nodes->size());
  for (const RouteEdge& edge : *edges) {
    const int a = static_cast<int>(edge.start);
    const int b = static_cast<int>(edge.end);
    neighbours[a].insert(b);
    neighbours[b].insert(a);
    if (edge.length >= min_distance) continue;
    PositionKey ka = KeyOf((*nodes)[a].position);
    PositionKey kb = KeyOf((*nodes)[b].position);
    candidates.push_back({edge.length, std::min(ka, kb), std::max(ka, kb), a, b});
  }
  if (candidates.empty()) return;
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.length, x.first, x.second) < std::tie(y.length, y.first, y.second);
  });
  // Whether `a` stays when it and `b` merge.
  auto stays = [&](int a, int b) {
    const RouteNode& x = (*nodes)[a];
    const RouteNode& y = (*nodes)[b];
    if (KindRank(x.kind) != KindRank(y.kind)) return KindRank(x.kind) > KindRank(y.kind);
    if (x.clearance != y.clearance) {
      return x.kind == RouteNodeKind::kDoorway ? x.clearance < y.clearance
                                               : x.clearance > y.clearance;
    }
    return KeyOf(x.position) < KeyOf(y.position);
  };
  std::vector<bool> alive(nodes->size(), true);
  for (const Candidate& candidate : candidates) {
    if (!alive[candidate.a] || !alive[candidate.b]) continue;
    if (neighbours[candidate.a].count(candidate.b) == 0) continue;
    const int keep = stays(candidate.a, candidate.b) ? candidate.a : candidate.b;
    const int drop = keep == candidate.a ? candidate.b : candidate.a;
    const Point2 at = (*nodes)[keep].position;
    const bool movable =
        std::all_of(neighbours[drop].begin(), neighbours[drop].end(), [&](int other) {
          return other == keep || neighbours[keep].count(other) > 0 ||
                 segments.Keeps(at, (*nodes)[other].position, required);
        });
    if (!movable) continue;
    for (const int other : neighbours[drop]) {
      neighbours[other].erase(drop);
      if (other == keep) continue;
      neighbours[other].insert(keep);
      neighbours[keep].insert(other);
    }
    neighbours[drop].clear();
    alive[drop] = false;
  }
  std::vector<int> index(nodes->size(), -1);
  std::vector<RouteNode> kept_nodes;
  for (size_t i = 0; i < nodes->size(); ++i) {
    if (!alive[i]) continue;
    index[i] = static_cast<int>(kept_nodes.size());
    kept_nodes.push_back((*nodes)[i]);
  }
  // The edges that stayed as they were keep their order and figures; moved ones are measured anew.
  std::vector<RouteEdge> kept_edges;
  std::set<std::pair<int, int>> present;
  for (RouteEdge edge : *edges) {
    const int a = static_cast<int>(edge.start);
    const int b = static_cast<int>(edge.end);
    if (!alive[a] || !alive[b]) continue;
    present.insert({std::min(a, b), std::max(a, b)});
    edge.start = static_cast<uint32_t>(index[a]);
    edge.end = static_cast<uint32_t>(index[b]);
    kept_edges.push_back(edge);
  }
  for (size_t a = 0; a < nodes->size(); ++a) {
    for (const int b : neighbours[a]) {
      if (static_cast<int>(a) > b || present.count({static_cast<int>(a), b}) > 0) continue;
      RouteEdge edge;
      edge.start = static_cast<uint32_t>(index[a]);
      edge.end = static_cast<uint32_t>(index[b]);
      edge.length = ((*nodes)[b].position - (*nodes)[a].position).norm();
      edge.clearance = segments.Clearance((*nodes)[a].position, (*nodes)[b].position);
      kept_edges.push_back(edge);
    }
  }
  *nodes = std::move(kept_nodes);
  *edges = std::move(kept_edges);
}

// Removes the parts of the graph a robot can move less than `min_length` in: their edges' length
// plus the widest circle its centre can move in around a node (twice the node's clearance beyond
// `node_clearance`). Pockets of free space the robot just fits in go; a room that shrank to its
// middle node stays. Indices are renumbered.
void DropSmallParts(double min_length, double node_clearance, std::vector<RouteNode>* nodes,
                    std::vector<RouteEdge>* edges) {
  std::vector<size_t> parent(nodes->size());
  std::iota(parent.begin(), parent.end(), size_t{0});
  auto find = [&parent](size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const RouteEdge& edge : *edges) parent[find(edge.start)] = find(edge.end);
  std::vector<double> length(nodes->size(), 0.0);
  for (const RouteEdge& edge : *edges) length[find(edge.start)] += edge.length;
  std::vector<double> extent(nodes->size(), 0.0);
  for (size_t i = 0; i < nodes->size(); ++i) {
    const size_t root = find(i);
    extent[root] = std::max(extent[root], 2.0 * ((*nodes)[i].clearance - node_clearance));
  }
  for (size_t i = 0; i < nodes->size(); ++i) length[i] += extent[i];
  std::vector<int> index(nodes->size(), -1);
  std::vector<RouteNode> kept_nodes;
  for (size_t i = 0; i < nodes->size(); ++i) {
    if (length[find(i)] < min_length) continue;
    index[i] = static_cast<int>(kept_nodes.size());
    kept_nodes.push_back((*nodes)[i]);
  }
  std::vector<RouteEdge> kept_edges;
  for (RouteEdge edge : *edges) {
    if (index[edge.start] < 0) continue;
    edge.start = static_cast<uint32_t>(index[edge.start]);
    edge.end = static_cast<uint32_t>(index[edge.end]);
    kept_edges.push_back(edge);
  }
  *nodes = std::move(kept_nodes);
  *edges = std::move(kept_edges);
}

}  // namespace

Status RouteGraphOptions::Validate() const {
  auto bad = [](const std::string& what) { return InvalidArgumentError("route graph: " + what); };
  if (!PositiveFinite(robot_radius)) return bad("robot_radius must be > 0");
  if (!std::isfinite(clearance_margin) || clearance_margin < 0.0) {
    return bad("clearance_margin must be >= 0");
  }
  if (!PositiveFinite(lane_spacing)) return bad("lane_spacing must be > 0");
  if (!std::isfinite(merge_distance) || merge_distance < 0.0) {
    return bad("merge_distance must be >= 0");
  }
  if (!std::isfinite(min_spur_length) || min_spur_length < 0.0) {
    return bad("min_spur_length must be >= 0");
  }
  if (!(doorway_ratio > 0.0 && doorway_ratio <= 1.0)) return bad("doorway_ratio must be in (0, 1]");
  if (!PositiveFinite(doorway_window)) return bad("doorway_window must be > 0");
  if (!PositiveFinite(tile_size)) return bad("tile_size must be > 0");
  if (!std::isfinite(shortcut_radius) || shortcut_radius < 0.0) {
    return bad("shortcut_radius must be >= 0");
  }
  if (!(shortcut_ratio >= 1.0) || !std::isfinite(shortcut_ratio)) {
    return bad("shortcut_ratio must be >= 1");
  }
  if (!std::isfinite(min_part_length) || min_part_length < 0.0) {
    return bad("min_part_length must be >= 0");
  }
  if (!std::isfinite(min_node_distance) || min_node_distance < 0.0) {
    return bad("min_node_distance must be >= 0");
  }
  if (!PositiveFinite(clearance_cap)) return bad("clearance_cap must be > 0");
  if (frame.empty()) return bad("frame must not be empty");
  return Status::Ok();
}

double RouteGraphOptions::ExactClearanceUpTo() const {
  return std::max(clearance_cap, robot_radius + clearance_margin + 1.0);
}

double RouteGraphOptions::MinNodeDistance() const {
  return min_node_distance > 0.0 ? min_node_distance : 2.0 * robot_radius;
}

void RouteGraphOptions::Describe(OptionsPrinter& out) const {
  out.Add("robot_radius", robot_radius);
  out.Add("clearance_margin", clearance_margin);
  out.Add("lane_spacing", lane_spacing);
  out.Add("merge_distance", merge_distance);
  out.Add("min_spur_length", min_spur_length);
  out.Add("doorway_ratio", doorway_ratio);
  out.Add("doorway_window", doorway_window);
  out.Add("clearance_cap", clearance_cap);
  out.Add("tile_size", tile_size);
  out.Add("shortcut_radius", shortcut_radius);
  out.Add("shortcut_ratio", shortcut_ratio);
  out.Add("min_part_length", min_part_length);
  out.Add("min_node_distance", min_node_distance);
  out.Add("frame", frame);
  out.Nested("thresholds", thresholds);
}

RouteGraphBuilder::RouteGraphBuilder(RouteGraphOptions options) : options_(std::move(options)) {
  const Status status = options_.Validate();
  FLEETMAP_CHECK(status.ok(), status.message());
}

double RouteGraphBuilder::NodeClearance() const {
  return options_.robot_radius + std::max(options_.clearance_margin, resolution_);
}

double RouteGraphBuilder::EdgeClearance() const { return NodeClearance() - resolution_; }

StatusOr<RouteGraph> RouteGraphBuilder::Build(const grid::OccupancyGrid& grid,
                                              const MapContext& context) {
  if (grid.empty()) return InvalidArgumentError("route graph: the grid is empty");
  if (std::abs(grid.origin().yaw) > 1e-9) {
    return InvalidArgumentError("route graph: the grid's origin is rotated (yaw " +
                                std::to_string(grid.origin().yaw) + " rad); it must be 0");
  }
  overlay_ = context.overlay != nullptr ? *context.overlay : RouteOverlay();
  const grid::OccupancyGrid opened = OpenedGrid(grid, overlay_);
  const grid::OccupancyGrid& source = overlay_.empty() ? grid : opened;
  resolution_ = source.resolution();
  origin_ = Point2(source.origin().x, source.origin().y);
  clearance_ = ClearanceMap(source, options_.ExactClearanceUpTo(), options_.thresholds);
  segment_memo_.Clear();
  skeleton_ = Skeleton(clearance_, NodeClearance());
  free_.assign(static_cast<size_t>(source.cell_count()), 0);
  for (int y = 0; y < source.height(); ++y) {
    for (int x = 0; x < source.width(); ++x) {
      free_[static_cast<size_t>(y) * source.width() + x] =
          source.StateAt(x, y, options_.thresholds) == grid::CellState::kFree ? 1 : 0;
    }
  }
  FindRoomCentres(context.rooms);
  RouteGraph graph = Extract();
  MarkOverlay(&graph);
  AssignIds(&graph);
  return graph;
}

void RouteGraphBuilder::FindRoomCentres(const scene::SubmapGraph* rooms) {
  room_centres_.clear();
  if (rooms == nullptr) return;
  for (const scene::Submap& submap : rooms->submaps) {
    if (submap.kind != scene::SubmapKind::kObserved) continue;
    const Transform2 map_from_submap = submap.map_from_submap.ToTransform();
    double best = -1.0;
    Point2 centre = Point2::Zero();
    const grid::OccupancyGrid& cells = submap.navigable;
    for (int y = 0; y < cells.height(); ++y) {
      for (int x = 0; x < cells.width(); ++x) {
        if (cells.StateAt(x, y) != grid::CellState::kFree) continue;
        const grid::CellIndex cell = clearance_.CellOf(map_from_submap * cells.CellCenter(x, y));
        if (!clearance_.Contains(cell.x, cell.y)) continue;
        const double value = clearance_.at(cell.x, cell.y);
        if (value > best) {
          best = value;
          centre = clearance_.CellCenter(cell.x, cell.y);
        }
      }
    }
    if (best >= NodeClearance()) room_centres_.push_back(centre);
  }
}

StatusOr<RouteGraph> RouteGraphBuilder::Update(const grid::OccupancyGrid& grid,
                                               const std::vector<grid::CellRect>& changed,
                                               const MapContext& context) {
  if (!previous_) return InvalidArgumentError("route graph: Update before any Build");
  if (grid.width() != clearance_.width() || grid.height() != clearance_.height() ||
      !grid::SameResolution(grid.resolution(), resolution_) ||
      Point2(grid.origin().x, grid.origin().y) != origin_ || std::abs(grid.origin().yaw) > 1e-9) {
    return InvalidArgumentError(
        "route graph: Update with a grid of another geometry than the last Build");
  }
  RouteOverlay overlay = context.overlay != nullptr ? *context.overlay : RouteOverlay();
  std::vector<grid::CellRect> windows = changed;
  const std::vector<grid::CellRect> overlay_changes =
      BlocksHolding(overlay.Differences(overlay_), grid.width(), grid.height(),
                    std::max(1, static_cast<int>(std::lround(options_.tile_size / resolution_))));
  windows.insert(windows.end(), overlay_changes.begin(), overlay_changes.end());
  overlay_ = std::move(overlay);
  const grid::OccupancyGrid opened = OpenedGrid(grid, overlay_);
  const grid::OccupancyGrid& source = overlay_.empty() ? grid : opened;
  // The cells whose state changed, per rectangle: their bounding box.
  std::vector<grid::CellRect> boxes;
  for (const grid::CellRect& rect : windows) {
    int x0 = source.width();
    int y0 = source.height();
    int x1 = -1;
    int y1 = -1;
    for (int y = std::max(rect.y0, 0); y < std::min(rect.y0 + rect.height, source.height()); ++y) {
      for (int x = std::max(rect.x0, 0); x < std::min(rect.x0 + rect.width, source.width()); ++x) {
        const uint8_t free =
            source.StateAt(x, y, options_.thresholds) == grid::CellState::kFree ? 1 : 0;
        uint8_t& known = free_[static_cast<size_t>(y) * source.width() + x];
        if (free == known) continue;
        known = free;
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
      }
    }
    if (x1 >= x0) boxes.push_back({x0, y0, x1 - x0 + 1, y1 - y0 + 1});
  }
  const std::vector<Point2> old_room_centres = room_centres_;
  if (!boxes.empty()) {
    const int reach = static_cast<int>(std::ceil(options_.ExactClearanceUpTo() / resolution_)) + 1;
    for (const grid::CellRect& box : boxes) {
      clearance_.Update(source, Dilate(box, reach));
      segment_memo_.Forget(Dilate(box, reach));
    }
    // The fitting cells change within the node clearance of a changed cell; a metre more lets
    // the skeleton find the middle of what changed again.
    constexpr double kContext = 1.0;
    const int region = static_cast<int>(std::ceil((NodeClearance() + kContext) / resolution_)) + 1;
    for (const grid::CellRect& box : boxes) {
      skeleton_.Update(clearance_, NodeClearance(), Dilate(box, region));
    }
  }
  FindRoomCentres(context.rooms);
  if (boxes.empty() && overlay_changes.empty() && room_centres_ == old_room_centres) {
    return *previous_;
  }
  RouteGraph graph = Extract();
  MarkOverlay(&graph);
  AssignIds(&graph);
  return graph;
}

void RouteGraphBuilder::MarkOverlay(RouteGraph* graph) const {
  if (overlay_.empty()) return;
  const int width = clearance_.width();
  auto cell_index = [&](const Point2& point) -> std::optional<int64_t> {
    const grid::CellIndex cell = clearance_.CellOf(point);
    if (!clearance_.Contains(cell.x, cell.y)) return std::nullopt;
    return static_cast<int64_t>(cell.y) * width + cell.x;
  };
  for (RouteNode& node : graph->nodes) {
    const std::optional<int64_t> cell = cell_index(node.position);
    node.predicted = cell && overlay_.Predicted(*cell);
  }
  // Each edge is looked at every quarter cell, as its clearance was proven.
  for (RouteEdge& edge : graph->edges) {
    const Point2 a = graph->nodes[edge.start].position;
    const Point2 b = graph->nodes[edge.end].position;
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / (resolution_ / 4))));
    for (int step = 0; step <= steps; ++step) {
      const std::optional<int64_t> cell = cell_index(a + (b - a) * (step / double(steps)));
      if (!cell) continue;
      if (overlay_.Predicted(*cell)) edge.predicted = true;
      if (!edge.blocking_object) edge.blocking_object = overlay_.ObjectAt(*cell);
    }
  }
}

RouteGraph RouteGraphBuilder::Extract() {
  SkeletonGraph skeleton_graph = internal::TraceSkeleton(skeleton_, clearance_);
  internal::PruneSpurs(clearance_, options_.min_spur_length, &skeleton_graph);
  internal::MergeNearJunctions(clearance_, options_.merge_distance, &skeleton_graph);

  const int width = skeleton_graph.width;
  auto point_of = [&](int cell) { return clearance_.CellCenter(cell % width, cell / width); };
  auto clearance_of = [&](int cell) {
    return static_cast<double>(clearance_.at(cell % width, cell / width));
  };
  Segments segments(clearance_, segment_memo_);
  Assembly assembly(segments, options_.lane_spacing);
  for (const internal::SkeletonNode& node : skeleton_graph.nodes) {
    if (node.alive) assembly.AddNode(point_of(node.cell), node.kind, clearance_of(node.cell));
  }
  for (const SkeletonBranch& branch : skeleton_graph.branches) {
    if (!branch.alive) continue;
    const std::vector<int>& cells = branch.cells;
    std::vector<Point2> points(cells.size());
    for (size_t i = 0; i < cells.size(); ++i) points[i] = point_of(cells[i]);
    std::vector<Cut> cuts = CutPoints(cells, width, clearance_, options_);
    if (cuts.empty() && branch.from == branch.to && cells.size() >= 4) {
      cuts.push_back({cells.size() / 2, RouteNodeKind::kLane});  // a loop needs a second node
    }
    std::vector<size_t> ends = {0};
    for (const Cut& cut : cuts) ends.push_back(cut.index);
    ends.push_back(cells.size() - 1);
    std::vector<RouteNodeKind> kinds(cells.size(), RouteNodeKind::kLane);
    for (const Cut& cut : cuts) kinds[cut.index] = cut.kind;
    for (size_t piece = 0; piece + 1 < ends.size(); ++piece) {
      const std::vector<size_t> corners =
          Straighten(points, ends[piece], ends[piece + 1], segments, EdgeClearance());
      int previous = -1;
      for (const size_t corner : corners) {
        const int node =
            assembly.AddNode(points[corner], kinds[corner], clearance_of(cells[corner]));
        if (previous >= 0) assembly.AddSegment(previous, node);
        previous = node;
      }
    }
  }
  // Room centres: the room's most open cell, joined to the nearest nodes it sees.
  for (const Point2& centre : room_centres_) {
    const grid::CellIndex cell = clearance_.CellOf(centre);
    if (!clearance_.Contains(cell.x, cell.y) || clearance_.at(cell.x, cell.y) < NodeClearance()) {
      continue;
    }
    std::vector<std::pair<double, int>> nearest;
    for (size_t i = 0; i < assembly.nodes().size(); ++i) {
      nearest.push_back({(assembly.nodes()[i].position - centre).norm(), static_cast<int>(i)});
    }
    std::sort(nearest.begin(), nearest.end());
    const int room =
        assembly.AddNode(centre, RouteNodeKind::kRoomCentre, clearance_.at(cell.x, cell.y));
    int joined = 0;
    for (const auto& [distance, index] : nearest) {
      if (joined >= 2 || distance > 2.0 * options_.lane_spacing) break;
      if (index == room) continue;
      if (!segments.Keeps(centre, assembly.nodes()[index].position, EdgeClearance())) {
        continue;
      }
      assembly.AddSegment(room, index);
      ++joined;
    }
  }
  if (options_.shortcut_radius > 0.0) {
    AddShortcuts(segments, EdgeClearance(), options_.shortcut_radius, options_.shortcut_ratio,
                 &assembly);
  }
  RouteGraph graph;
  graph.frame = options_.frame;
  graph.robot_radius = options_.robot_radius;
  graph.clearance_margin = std::max(options_.clearance_margin, resolution_);
  graph.nodes = std::move(assembly.nodes());
  graph.edges = std::move(assembly.edges());
  MergeCloseNodes(segments, EdgeClearance(), options_.MinNodeDistance(), &graph.nodes,
                  &graph.edges);
  // Junctions and dead ends by what the straightened graph has at them.
  std::vector<int> degree(graph.nodes.size(), 0);
  for (const RouteEdge& edge : graph.edges) {
    ++degree[edge.start];
    ++degree[edge.end];
  }
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    RouteNode& node = graph.nodes[i];
    if (node.kind != RouteNodeKind::kJunction && node.kind != RouteNodeKind::kDeadEnd) continue;
    node.kind = degree[i] >= 3 ? RouteNodeKind::kJunction : RouteNodeKind::kDeadEnd;
  }
  DropSmallParts(options_.min_part_length, NodeClearance(), &graph.nodes, &graph.edges);
  std::ostringstream message;
  if (graph.nodes.empty()) {
    const float widest =
        clearance_.values().empty()
            ? 0.0F
            : *std::max_element(clearance_.values().begin(), clearance_.values().end());
    message << "empty route graph: a robot of radius " << ShortNumber(options_.robot_radius)
            << " m needs " << FixedNumber(NodeClearance(), 3)
            << " m of clearance (radius + margin) and the widest free space of the map has "
            << FixedNumber(std::max(0.0F, widest), 2) << " m: ";
    if (widest < NodeClearance()) {
      message << "the robot fits nowhere (no doorway or corridor is wide enough)";
    } else {
      message << "the robot fits only in pockets with less than "
              << ShortNumber(options_.min_part_length) << " m of route in them";
    }
  } else {
    const int parts = CountComponents(graph.nodes.size(), graph.edges);
    if (parts > 1) {
      message << "the route graph has " << parts
              << " parts not connected to each other: a robot of radius "
              << ShortNumber(options_.robot_radius) << " m (" << FixedNumber(NodeClearance(), 3)
              << " m of clearance) does not fit through what joins them, or the map does not "
                 "join them";
    }
  }
  graph.message = message.str();
  return graph;
}

void RouteGraphBuilder::AssignIds(RouteGraph* graph) {
  std::map<PositionKey, uint32_t> old_nodes;
  std::map<std::pair<uint32_t, uint32_t>, const RouteEdge*> old_edges;
  if (previous_) {
    for (const RouteNode& node : previous_->nodes) old_nodes.emplace(KeyOf(node.position), node.id);
    for (const RouteEdge& edge : previous_->edges) {
      old_edges.emplace(
          std::make_pair(std::min(edge.start, edge.end), std::max(edge.start, edge.end)), &edge);
    }
  }
  std::set<uint32_t> used;
  for (RouteNode& node : graph->nodes) {
    const auto found = old_nodes.find(KeyOf(node.position));
    if (found != old_nodes.end() && used.insert(found->second).second) {
      node.id = found->second;
    } else {
      node.id = next_id_++;
    }
  }
  for (RouteEdge& edge : graph->edges) {
    edge.start = graph->nodes[edge.start].id;
    edge.end = graph->nodes[edge.end].id;
    const auto found =
        old_edges.find({std::min(edge.start, edge.end), std::max(edge.start, edge.end)});
    if (found != old_edges.end()) {
      const RouteEdge& old = *found->second;
      edge.id = old.id;
      edge.reverse_id = old.reverse_id;
      if (edge.start != old.start) std::swap(edge.start, edge.end);
    } else {
      edge.id = next_id_++;
      edge.reverse_id = next_id_++;
    }
  }
  std::sort(graph->nodes.begin(), graph->nodes.end(),
            [](const RouteNode& a, const RouteNode& b) { return a.id < b.id; });
  std::sort(graph->edges.begin(), graph->edges.end(),
            [](const RouteEdge& a, const RouteEdge& b) { return a.id < b.id; });
  previous_ = *graph;
}

}  // namespace fleetmap::route_graph
