#include "common/vector_map/vectorizer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <vector>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/free_space_extractor.hpp"
#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

// A polyline in cell coordinates while it is being built.
struct CellPolyline {
  std::vector<Point2> points;
  bool closed = false;
  bool start_on_border = false;  // ends at a tile-border node: never merged there
  bool end_on_border = false;
};

// The 8 neighbours in cyclic order: E, NE, N, NW, W, SW, S, SE.
constexpr std::array<int, 8> kDx = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr std::array<int, 8> kDy = {0, 1, 1, 1, 0, -1, -1, -1};

// simple[mask]: deleting a pixel whose foreground 8-neighbourhood is `mask` (bit k = neighbour k)
// keeps the topology (one 8-connected foreground component around it and one 4-connected
// background component touching it) and does not shorten a line (at least two neighbours).
std::array<bool, 256> BuildSimpleTable() {
  std::array<bool, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    auto set = [&](int k) { return ((mask >> k) & 1) != 0; };
    auto count_components = [&](bool foreground, bool eight) {
      std::array<int, 8> label{};
      label.fill(-1);
      int components = 0;
      for (int start = 0; start < 8; ++start) {
        if (set(start) != foreground || label[start] >= 0) continue;
        // Background components only count if they touch the pixel through a 4-neighbour.
        std::array<int, 8> stack{};
        int top = 0;
        stack[top++] = start;
        label[start] = components;
        bool touches = foreground;
        while (top > 0) {
          const int k = stack[--top];
          if (k % 2 == 0) touches = true;
          for (int j = 0; j < 8; ++j) {
            if (set(j) != foreground || label[j] >= 0) continue;
            const int ddx = std::abs(kDx[j] - kDx[k]);
            const int ddy = std::abs(kDy[j] - kDy[k]);
            const bool adjacent = eight ? std::max(ddx, ddy) == 1 : ddx + ddy == 1;
            if (adjacent) {
              label[j] = components;
              stack[top++] = j;
            }
          }
        }
        if (touches) ++components;
      }
      return components;
    };
    const int count = std::popcount(static_cast<unsigned>(mask));
    table[mask] =
        count >= 2 && count_components(true, true) == 1 && count_components(false, false) == 1;
  }
  return table;
}

const std::array<bool, 256>& SimpleTable() {
  static const std::array<bool, 256> table = BuildSimpleTable();
  return table;
}

// Greedy chain simplification with a full check. `valid(i, j)` says whether the segment from
// vertex i to vertex j may replace vertices i..j; unit steps (j = i + 1) that are not valid break
// the chain. From each kept vertex it doubles the reach while valid, then bisects.
template <typename Valid>
void SimplifyChain(const std::vector<Point2>& points, Valid&& valid,
                   std::vector<std::vector<int>>& pieces) {
  const int n = static_cast<int>(points.size());
  if (n == 0) return;
  std::vector<int> current = {0};
  int i = 0;
  while (i < n - 1) {
    if (!valid(i, i + 1)) {
      if (current.size() >= 2) pieces.push_back(std::move(current));
      current.clear();
      ++i;
      current.push_back(i);
      continue;
    }
    int lo = i + 1;
    int hi = -1;
    int step = 2;
    while (lo < n - 1) {
      const int candidate = std::min(i + step, n - 1);
      if (valid(i, candidate)) {
        lo = candidate;
        step *= 2;
      } else {
        hi = candidate;
        break;
      }
    }
    while (hi != -1 && hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      if (valid(i, mid)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    current.push_back(lo);
    i = lo;
  }
  if (current.size() >= 2 || n == 1) pieces.push_back(std::move(current));
}

// Turns a simplified piece whose ends coincide into a closed ring (or a point).
CellPolyline MakePolyline(const std::vector<Point2>& points, const std::vector<int>& piece) {
  CellPolyline polyline;
  polyline.points.reserve(piece.size());
  for (const int index : piece) polyline.points.push_back(points[index]);
  if (polyline.points.size() >= 2 && polyline.points.front() == polyline.points.back()) {
    polyline.points.pop_back();
    polyline.closed = polyline.points.size() >= 3;
  }
  return polyline;
}

// Joins open polylines that end at the same (non-border) point, two by two, so that a vertex
// shared at a junction or a corner is stored once per pair rather than once per polyline.
std::vector<CellPolyline> MergeAtSharedEnds(std::vector<CellPolyline> polylines) {
  const int n = static_cast<int>(polylines.size());
  auto key_of = [](const Point2& p) {
    const int64_t kx = std::llround(p.x() * 2.0);
    const int64_t ky = std::llround(p.y() * 2.0);
    return (kx << 32) ^ (ky & 0xffffffffLL);
  };
  auto mergeable = [&](int i) { return !polylines[i].closed && polylines[i].points.size() >= 2; };
  std::unordered_map<int64_t, int> waiting;  // end point -> an unpaired end id
  std::vector<int> partner(2 * static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (!mergeable(i)) continue;
    for (int side = 0; side < 2; ++side) {
      const bool on_border = side == 0 ? polylines[i].start_on_border : polylines[i].end_on_border;
      if (on_border) continue;
      const Point2& p = side == 0 ? polylines[i].points.front() : polylines[i].points.back();
      const int end = 2 * i + side;
      auto [it, inserted] = waiting.try_emplace(key_of(p), end);
      if (!inserted) {
        partner[end] = it->second;
        partner[it->second] = end;
        waiting.erase(it);
      }
    }
  }
  std::vector<CellPolyline> merged;
  std::vector<bool> used(n, false);
  auto walk = [&](int start_end, bool cycle) {
    CellPolyline out;
    int end = start_end;
    out.start_on_border =
        (end % 2 == 0) ? polylines[end / 2].start_on_border : polylines[end / 2].end_on_border;
    while (true) {
      const int i = end / 2;
      used[i] = true;
      const auto& pts = polylines[i].points;
      const bool forward = end % 2 == 0;
      const size_t skip = out.points.empty() ? 0 : 1;
      for (size_t k = skip; k < pts.size(); ++k) {
        out.points.push_back(forward ? pts[k] : pts[pts.size() - 1 - k]);
      }
      const int exit_end = forward ? 2 * i + 1 : 2 * i;
      out.end_on_border = forward ? polylines[i].end_on_border : polylines[i].start_on_border;
      const int next = partner[exit_end];
      if (next < 0 || used[next / 2]) break;
      end = next;
    }
    if (cycle && out.points.size() >= 2 && out.points.front() == out.points.back()) {
      out.points.pop_back();
      out.closed = out.points.size() >= 3;
    }
    merged.push_back(std::move(out));
  };
  for (int i = 0; i < n; ++i) {
    if (used[i]) continue;
    if (!mergeable(i)) {
      used[i] = true;
      merged.push_back(std::move(polylines[i]));
      continue;
    }
    if (partner[2 * i] < 0) {
      walk(2 * i, false);
    } else if (partner[2 * i + 1] < 0) {
      walk(2 * i + 1, false);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) walk(2 * i, true);  // what is left are cycles
  }
  return merged;
}

// Working state of one VectorizeTile call in kDefault mode.
class DefaultTileVectorizer {
 public:
  DefaultTileVectorizer(const Delimitation& delimitation, const CellRect& rect, double epsilon)
      : d_(delimitation),
        rect_(rect),
        eps_(epsilon),
        eps2_(ToleratedSquare(epsilon)),
        pw_(rect.width + 2),
        ph_(rect.height + 2) {}

  std::vector<CellPolyline> Run() {
    BuildSkeletonInput();
    Thin();
    TraceChains();
    AttachBorderNodes();
    AssignDelimitation();
    std::vector<CellPolyline> polylines;
    SimplifySkeletonChains(polylines);
    polylines = MergeAtSharedEnds(std::move(polylines));
    CoverRemaining(polylines);
    return polylines;
  }

 private:
  static constexpr uint8_t kEmpty = 0;
  static constexpr uint8_t kSkeleton = 1;
  static constexpr uint8_t kAnchor = 2;  // occupied cell just outside the tile: fixed

  int Local(int x, int y) const { return (y - rect_.y0 + 1) * pw_ + (x - rect_.x0 + 1); }
  int LocalX(int index) const { return index % pw_ - 1 + rect_.x0; }
  int LocalY(int index) const { return index / pw_ - 1 + rect_.y0; }
  int Offset(int k) const { return kDy[k] * pw_ + kDx[k]; }
  Point2 CellPoint(int index) const { return Point2(LocalX(index), LocalY(index)); }
  size_t RectIndex(int x, int y) const {
    return static_cast<size_t>(y - rect_.y0) * rect_.width + (x - rect_.x0);
  }

  // An occupied cell is kept for thinning if a non-occupied cell is within city-block distance 2
  // (so thick blobs become rings about two cells wide, and thinning takes a few passes).
  bool NearBoundary(int x, int y) const {
    static constexpr std::array<std::array<int, 2>, 12> kRing = {{{1, 0},
                                                                  {-1, 0},
                                                                  {0, 1},
                                                                  {0, -1},
                                                                  {2, 0},
                                                                  {-2, 0},
                                                                  {0, 2},
                                                                  {0, -2},
                                                                  {1, 1},
                                                                  {1, -1},
                                                                  {-1, 1},
                                                                  {-1, -1}}};
    for (const auto& o : kRing) {
      if (!d_.Occupied(x + o[0], y + o[1])) return true;
    }
    return false;
  }

  void BuildSkeletonInput() {
    pixels_.assign(static_cast<size_t>(pw_) * ph_, kEmpty);
    for (int y = rect_.y0 - 1; y <= rect_.y0 + rect_.height; ++y) {
      for (int x = rect_.x0 - 1; x <= rect_.x0 + rect_.width; ++x) {
        if (!d_.Occupied(x, y)) continue;
        if (rect_.Contains(x, y)) {
          if (NearBoundary(x, y)) {
            pixels_[Local(x, y)] = kSkeleton;
            list_.push_back(Local(x, y));
          }
        } else {
          pixels_[Local(x, y)] = kAnchor;
        }
      }
    }
  }

  int Mask(int index) const {
    int mask = 0;
    for (int k = 0; k < 8; ++k) {
      if (pixels_[index + Offset(k)] != kEmpty) mask |= 1 << k;
    }
    return mask;
  }

  // Directional sequential thinning: each pass deletes, among the pixels that were open on one
  // side when the pass began, those that are still simple (or line ends); passes rotate N, S, E, W.
  // A pixel is only deleted if every delimitation point within epsilon of it keeps another
  // skeleton pixel within epsilon: the skeleton never walks away from the boundary it stands for
  // (corners are kept) and redundant spurs are eaten, which avoids junctions.
  void Thin() {
    const auto& simple = SimpleTable();
    const int r = static_cast<int>(std::ceil(eps_));
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (dx * dx + dy * dy <= eps2_) window_.push_back({dx, dy});
      }
    }
    support_.assign(static_cast<size_t>(rect_.cell_count()), 0);
    for (const int index : list_) {
      const int x = LocalX(index);
      const int y = LocalY(index);
      for (const auto& [dx, dy] : window_) {
        if (rect_.Contains(x + dx, y + dy)) ++support_[RectIndex(x + dx, y + dy)];
      }
    }
    auto removable = [&](int index) {
      const int x = LocalX(index);
      const int y = LocalY(index);
      for (const auto& [dx, dy] : window_) {
        if (!rect_.Contains(x + dx, y + dy)) continue;
        if (support_[RectIndex(x + dx, y + dy)] <= 1 && d_.IsDelimitation(x + dx, y + dy)) {
          return false;
        }
      }
      return true;
    };
    static constexpr std::array<int, 4> kSides = {2, 6, 0, 4};  // N, S, E, W
    std::vector<int> candidates;
    bool changed = true;
    while (changed) {
      changed = false;
      for (const int side : kSides) {
        candidates.clear();
        for (const int index : list_) {
          if (pixels_[index + Offset(side)] == kEmpty) candidates.push_back(index);
        }
        bool deleted = false;
        for (const int index : candidates) {
          const int mask = Mask(index);
          const bool line_end = std::popcount(static_cast<unsigned>(mask)) == 1;
          if (!(simple[mask] || line_end) || !removable(index)) continue;
          pixels_[index] = kEmpty;
          const int x = LocalX(index);
          const int y = LocalY(index);
          for (const auto& [dx, dy] : window_) {
            if (rect_.Contains(x + dx, y + dy)) --support_[RectIndex(x + dx, y + dy)];
          }
          deleted = true;
        }
        if (deleted) {
          changed = true;
          std::erase_if(list_, [&](int index) { return pixels_[index] != kSkeleton; });
        }
      }
    }
  }

  // m-adjacency: a diagonal neighbour only counts when neither shared 4-neighbour is skeleton, so
  // an L-shaped corner or a little triangle of pixels reads as a path, not as a junction.
  bool Linked(int index, int k) const {
    if (pixels_[index + Offset(k)] != kSkeleton) return false;
    if (k % 2 == 0) return true;
    return pixels_[index + Offset((k + 7) % 8)] != kSkeleton &&
           pixels_[index + Offset((k + 1) % 8)] != kSkeleton;
  }

  int Degree(int index) const {
    int degree = 0;
    for (int k = 0; k < 8; ++k) degree += Linked(index, k);
    return degree;
  }

  void TraceChains() {
    degree_.assign(pixels_.size(), 0);
    for (const int index : list_) degree_[index] = static_cast<uint8_t>(Degree(index));
    std::vector<uint8_t> visited(pixels_.size(), 0);
    auto terminal = [&](int index) { return degree_[index] != 2; };
    for (const int p : list_) {
      if (!terminal(p)) continue;
      if (degree_[p] == 0) {
        chains_.push_back({p});
        continue;
      }
      for (int k = 0; k < 8; ++k) {
        const int q = p + Offset(k);
        if (!Linked(p, k)) continue;
        if (terminal(q)) {
          if (p < q) chains_.push_back({p, q});
          continue;
        }
        if (visited[q]) continue;
        std::vector<int> chain = {p};
        int previous = p;
        int current = q;
        while (!terminal(current) && !visited[current]) {
          visited[current] = 1;
          chain.push_back(current);
          int next = -1;
          for (int j = 0; j < 8; ++j) {
            const int r = current + Offset(j);
            if (Linked(current, j) && r != previous && (terminal(r) || !visited[r] || r == p)) {
              next = r;
              break;
            }
          }
          if (next < 0) break;
          previous = current;
          current = next;
        }
        if (terminal(current)) chain.push_back(current);
        chains_.push_back(std::move(chain));
      }
    }
    for (const int p : list_) {  // rings of degree-2 pixels
      if (terminal(p) || visited[p]) continue;
      std::vector<int> chain = {p};
      visited[p] = 1;
      int previous = -1;
      int current = p;
      while (true) {
        int next = -1;
        for (int j = 0; j < 8; ++j) {
          const int r = current + Offset(j);
          if (!Linked(current, j) || r == previous) continue;
          if (r == p && chain.size() > 2) {
            next = r;
            break;
          }
          if (!visited[r]) {
            next = r;
            break;
          }
        }
        if (next < 0) break;
        chain.push_back(next);
        if (next == p) break;
        visited[next] = 1;
        previous = current;
        current = next;
      }
      chains_.push_back(std::move(chain));
    }
  }

  // Whether cells (x, y) and its neighbour across a border are both occupied.
  bool Crossing(int x_inner, int y_inner, int x_outer, int y_outer) const {
    return d_.Occupied(x_inner, y_inner) && d_.Occupied(x_outer, y_outer);
  }

  // The border node for an end pixel next to anchors across one side of the tile. `along` is the
  // unit step along the border, `out` the unit step across it. Depends only on the two lines of
  // cells on either side of the border, so the neighbour tile finds the same point.
  std::optional<Point2> BorderNode(int x, int y, int out_x, int out_y) const {
    const int along_x = out_y != 0 ? 1 : 0;
    const int along_y = out_x != 0 ? 1 : 0;
    auto crossing_at = [&](int t) {
      return Crossing(x + t * along_x, y + t * along_y, x + t * along_x + out_x,
                      y + t * along_y + out_y);
    };
    int t0 = 0;
    bool found = crossing_at(0);
    if (!found && crossing_at(-1)) {
      t0 = -1;
      found = true;
    } else if (!found && crossing_at(1)) {
      t0 = 1;
      found = true;
    }
    const Point2 inner(x, y);
    const Point2 half_out(0.5 * out_x, 0.5 * out_y);
    const Point2 along(along_x, along_y);
    if (!found) {
      // Only a diagonal anchor: end at the cell corner shared with it.
      for (const int t : {-1, 1}) {
        if (d_.Occupied(x + t * along_x + out_x, y + t * along_y + out_y)) {
          return inner + half_out + 0.5 * t * along;
        }
      }
      return std::nullopt;
    }
    int lo = t0;
    int hi = t0;
    const int limit = std::max(d_.grid().width(), d_.grid().height());
    while (lo - 1 > -limit && crossing_at(lo - 1)) --lo;
    while (hi + 1 < limit && crossing_at(hi + 1)) ++hi;
    const int length = hi - lo + 1;
    if (length <= 3) return inner + half_out + 0.5 * (lo + hi) * along;
    const Point2 first = inner + half_out + (lo + 0.5) * along;
    const Point2 last = inner + half_out + (hi - 0.5) * along;
    return std::abs(lo + 0.5) <= std::abs(hi - 0.5) ? first : last;
  }

  std::optional<Point2> BorderNodeFor(int index) const {
    const int x = LocalX(index);
    const int y = LocalY(index);
    struct Side {
      bool at;
      int out_x;
      int out_y;
    };
    const std::array<Side, 4> sides = {{{x == rect_.x0, -1, 0},
                                        {x == rect_.x0 + rect_.width - 1, 1, 0},
                                        {y == rect_.y0, 0, -1},
                                        {y == rect_.y0 + rect_.height - 1, 0, 1}}};
    for (const Side& side : sides) {
      if (!side.at) continue;
      const int along_x = side.out_y != 0 ? 1 : 0;
      const int along_y = side.out_x != 0 ? 1 : 0;
      bool anchored = false;
      for (int t = -1; t <= 1; ++t) {
        const int ax = x + side.out_x + t * along_x;
        const int ay = y + side.out_y + t * along_y;
        if (pixels_[Local(ax, ay)] == kAnchor) anchored = true;
      }
      if (!anchored) continue;
      if (auto node = BorderNode(x, y, side.out_x, side.out_y)) return node;
    }
    return std::nullopt;
  }

  // Chains become point lists; a chain end with at most one skeleton neighbour and an anchor
  // across the tile border is extended to the border node.
  void AttachBorderNodes() {
    chain_points_.resize(chains_.size());
    chain_border_.assign(chains_.size(), {false, false});
    for (size_t c = 0; c < chains_.size(); ++c) {
      auto& points = chain_points_[c];
      for (const int index : chains_[c]) points.push_back(CellPoint(index));
      if (rect_.width == 0) continue;
      const bool ring = chains_[c].size() > 1 && chains_[c].front() == chains_[c].back();
      if (ring) continue;
      for (int side = 0; side < 2; ++side) {
        const int end = side == 0 ? chains_[c].front() : chains_[c].back();
        if (degree_[end] > 1) continue;
        if (chains_[c].size() == 1 && side == 1 && chain_border_[c][0]) continue;
        const auto node = BorderNodeFor(end);
        if (!node || !SegmentContinuous(CellPoint(end), *node, eps_, d_)) continue;
        if (side == 0) {
          points.insert(points.begin(), *node);
          chain_border_[c][0] = true;
        } else {
          points.push_back(*node);
          chain_border_[c][1] = true;
        }
      }
      // A lone pixel with one node: that node is its end.
    }
  }

  // Each delimitation point of the tile is attached to its nearest skeleton pixel within epsilon
  // that is interior to a chain; simplifying that chain must keep it within epsilon. Points nearest
  // to a chain end need nothing: the end is always a vertex.
  void AssignDelimitation() {
    std::vector<int> chain_of(pixels_.size(), -1);
    std::vector<int> position_of(pixels_.size(), -1);
    chain_offset_.assign(chains_.size() + 1, 0);
    for (size_t c = 0; c < chains_.size(); ++c) {
      chain_offset_[c + 1] = chain_offset_[c] + static_cast<int>(chain_points_[c].size());
      const int shift = chain_border_[c][0] ? 1 : 0;
      if (PureRing(c)) {
        chain_of[chains_[c][0]] = static_cast<int>(c);
        position_of[chains_[c][0]] = 0;
      }
      for (size_t k = 1; k + 1 < chains_[c].size(); ++k) {
        chain_of[chains_[c][k]] = static_cast<int>(c);
        position_of[chains_[c][k]] = static_cast<int>(k) + shift;
      }
    }
    const int r = static_cast<int>(std::ceil(eps_));
    std::vector<std::pair<int, Point2>> attached;  // (global chain position, point)
    for (int y = rect_.y0; y < rect_.y0 + rect_.height; ++y) {
      for (int x = rect_.x0; x < rect_.x0 + rect_.width; ++x) {
        if (!d_.IsDelimitation(x, y)) continue;
        int best = -1;
        double best2 = eps2_;
        for (int dy = -r; dy <= r; ++dy) {
          for (int dx = -r; dx <= r; ++dx) {
            if (!rect_.Contains(x + dx, y + dy)) continue;
            const int index = Local(x + dx, y + dy);
            if (pixels_[index] != kSkeleton) continue;
            const double dist2 = dx * dx + dy * dy;
            if (dist2 <= best2 && (best < 0 || dist2 < best2)) {
              best = index;
              best2 = dist2;
            }
          }
        }
        if (best < 0 || chain_of[best] < 0) continue;
        attached.emplace_back(chain_offset_[chain_of[best]] + position_of[best], Point2(x, y));
      }
    }
    bucket_start_.assign(static_cast<size_t>(chain_offset_.back()) + 1, 0);
    for (const auto& [position, point] : attached) ++bucket_start_[position + 1];
    for (size_t i = 1; i < bucket_start_.size(); ++i) bucket_start_[i] += bucket_start_[i - 1];
    bucket_points_.resize(attached.size());
    std::vector<int> fill(bucket_start_.begin(), bucket_start_.end() - 1);
    for (const auto& [position, point] : attached) bucket_points_[fill[position]++] = point;
  }

  // A chain that closes on itself through degree-2 pixels only (no junction on it).
  bool PureRing(size_t c) const {
    const auto& chain = chains_[c];
    return chain.size() > 2 && chain.front() == chain.back() && degree_[chain.front()] == 2;
  }

  void SimplifySkeletonChains(std::vector<CellPolyline>& out) {
    std::vector<std::vector<int>> pieces;
    std::vector<Point2> rotated;
    for (size_t c = 0; c < chains_.size(); ++c) {
      const auto& points = chain_points_[c];
      const int base = chain_offset_[c];
      const int n = static_cast<int>(points.size());
      // Vertex m of the chain being simplified is vertex (m + shift) mod period of the chain.
      int shift = 0;
      int period = n;
      auto valid = [&](int i, int j) {
        const Point2& a = (shift == 0 ? points : rotated)[i];
        const Point2& b = (shift == 0 ? points : rotated)[j];
        if (j > i + 1) {
          for (int m = i; m <= j; ++m) {
            const int position = base + (m + shift) % period;
            for (int k = bucket_start_[position]; k < bucket_start_[position + 1]; ++k) {
              if (PointSegmentDistanceSquared(bucket_points_[k], a, b) > eps2_) return false;
            }
          }
        }
        return SegmentContinuous(a, b, eps_, d_);
      };
      pieces.clear();
      SimplifyChain(points, valid, pieces);
      if (PureRing(c) && n > 3 && pieces.size() == 1 && pieces[0].size() > 3) {
        // A ring's first vertex is arbitrary: start again from the first corner found, which
        // usually saves that vertex.
        period = n - 1;
        shift = pieces[0][1];
        rotated.clear();
        for (int m = 0; m <= period; ++m) rotated.push_back(points[(m + shift) % period]);
        std::vector<std::vector<int>> again;
        SimplifyChain(rotated, valid, again);
        if (again.size() == 1 && again[0].size() < pieces[0].size()) {
          out.push_back(MakePolyline(rotated, again[0]));
          continue;
        }
        shift = 0;
      }
      const int last = n - 1;
      for (const auto& piece : pieces) {
        CellPolyline polyline = MakePolyline(points, piece);
        polyline.start_on_border = chain_border_[c][0] && piece.front() == 0;
        polyline.end_on_border = chain_border_[c][1] && piece.back() == last;
        out.push_back(std::move(polyline));
      }
    }
  }

  // Marks the tile's delimitation points within epsilon of an emitted segment; the uncovered ones
  // are chained through 8-neighbours and simplified against themselves.
  void CoverRemaining(std::vector<CellPolyline>& polylines) {
    std::vector<uint8_t> covered(static_cast<size_t>(rect_.cell_count()), 0);
    auto rect_index = [&](int x, int y) {
      return static_cast<size_t>(y - rect_.y0) * rect_.width + (x - rect_.x0);
    };
    auto mark = [&](const Point2& a, const Point2& b) {
      ForEachCellNearSegment(a, b, eps_, [&](int x, int y) {
        if (!rect_.Contains(x, y) || covered[rect_index(x, y)]) return;
        if (PointSegmentDistanceSquared(Point2(x, y), a, b) <= eps2_) covered[rect_index(x, y)] = 1;
      });
    };
    for (const CellPolyline& polyline : polylines) {
      const auto& pts = polyline.points;
      if (pts.size() == 1) mark(pts[0], pts[0]);
      for (size_t k = 0; k + 1 < pts.size(); ++k) mark(pts[k], pts[k + 1]);
      if (polyline.closed) mark(pts.back(), pts.front());
    }
    auto open = [&](int x, int y) {
      return rect_.Contains(x, y) && !covered[rect_index(x, y)] && d_.IsDelimitation(x, y);
    };
    // 4-neighbours first, so that walks follow outlines rather than cut corners.
    static constexpr std::array<int, 8> kOrder = {0, 2, 4, 6, 1, 3, 5, 7};
    std::vector<Point2> chain;
    std::vector<std::vector<int>> pieces;
    for (int y = rect_.y0; y < rect_.y0 + rect_.height; ++y) {
      for (int x = rect_.x0; x < rect_.x0 + rect_.width; ++x) {
        if (!open(x, y)) continue;
        covered[rect_index(x, y)] = 1;
        std::vector<Point2> forward = {Point2(x, y)};
        std::vector<Point2> backward;
        for (auto* walk : {&forward, &backward}) {
          int cx = x;
          int cy = y;
          while (true) {
            bool moved = false;
            for (const int k : kOrder) {
              if (open(cx + kDx[k], cy + kDy[k])) {
                cx += kDx[k];
                cy += kDy[k];
                covered[rect_index(cx, cy)] = 1;
                walk->push_back(Point2(cx, cy));
                moved = true;
                break;
              }
            }
            if (!moved) break;
          }
        }
        chain.assign(backward.rbegin(), backward.rend());
        chain.insert(chain.end(), forward.begin(), forward.end());
        auto valid = [&](int i, int j) {
          const Point2& a = chain[i];
          const Point2& b = chain[j];
          for (int k = i + 1; k < j; ++k) {
            if (PointSegmentDistanceSquared(chain[k], a, b) > eps2_) return false;
          }
          return SegmentContinuous(a, b, eps_, d_);
        };
        pieces.clear();
        SimplifyChain(chain, valid, pieces);
        for (const auto& piece : pieces) polylines.push_back(MakePolyline(chain, piece));
      }
    }
  }

  const Delimitation& d_;
  CellRect rect_;
  double eps_;
  double eps2_;
  int pw_;
  int ph_;
  std::vector<uint8_t> pixels_;
  std::vector<int> list_;
  std::vector<std::pair<int, int>> window_;  // offsets within epsilon
  std::vector<uint16_t> support_;            // per tile cell: skeleton pixels within epsilon
  std::vector<uint8_t> degree_;
  std::vector<std::vector<int>> chains_;
  std::vector<std::vector<Point2>> chain_points_;
  std::vector<std::array<bool, 2>> chain_border_;
  std::vector<int> chain_offset_;
  std::vector<int> bucket_start_;
  std::vector<Point2> bucket_points_;
};

// The paper's heuristic (ALGORITHMS.md 1): graph on P with edges between points within epsilon,
// then shortcut removal of degree-2 vertices while dist(v2, seg(v1, v3)) < epsilon.
std::vector<CellPolyline> PaperVectorize(const Delimitation& d, const CellRect& rect, double eps) {
  const double eps2 = ToleratedSquare(eps);
  std::vector<int> id(static_cast<size_t>(rect.cell_count()), -1);
  std::vector<Point2> vertex;
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    for (int x = rect.x0; x < rect.x0 + rect.width; ++x) {
      if (!d.IsDelimitation(x, y)) continue;
      id[static_cast<size_t>(y - rect.y0) * rect.width + (x - rect.x0)] =
          static_cast<int>(vertex.size());
      vertex.emplace_back(x, y);
    }
  }
  const int n = static_cast<int>(vertex.size());
  std::vector<std::vector<int>> adjacency(n);
  const int r = static_cast<int>(std::floor(eps + kDistanceTolerance));
  for (int v = 0; v < n; ++v) {
    const int x = static_cast<int>(vertex[v].x());
    const int y = static_cast<int>(vertex[v].y());
    for (int dy = 0; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (dy == 0 && dx <= 0) continue;
        if (dx * dx + dy * dy > eps2 || !rect.Contains(x + dx, y + dy)) continue;
        const int u = id[static_cast<size_t>(y + dy - rect.y0) * rect.width + (x + dx - rect.x0)];
        if (u < 0) continue;
        adjacency[v].push_back(u);
        adjacency[u].push_back(v);
      }
    }
  }
  std::vector<int> queue(n);
  for (int v = 0; v < n; ++v) queue[v] = n - 1 - v;  // pop_back takes them in scan order
  std::vector<uint8_t> queued(n, 1);
  std::vector<uint8_t> removed(n, 0);
  while (!queue.empty()) {
    const int v2 = queue.back();
    queue.pop_back();
    queued[v2] = 0;
    if (adjacency[v2].size() != 2) continue;
    const int v1 = adjacency[v2][0];
    const int v3 = adjacency[v2][1];
    const double dist2 = PointSegmentDistanceSquared(vertex[v2], vertex[v1], vertex[v3]);
    if (!(dist2 < eps * eps)) continue;
    std::erase(adjacency[v1], v2);
    std::erase(adjacency[v3], v2);
    adjacency[v2].clear();
    removed[v2] = 1;
    if (std::find(adjacency[v1].begin(), adjacency[v1].end(), v3) == adjacency[v1].end()) {
      adjacency[v1].push_back(v3);
      adjacency[v3].push_back(v1);
    }
    for (const int w : {v1, v3}) {
      if (!queued[w]) {
        queued[w] = 1;
        queue.push_back(w);
      }
    }
  }
  // Decompose the remaining graph into polylines through degree-2 vertices.
  std::vector<CellPolyline> out;
  std::vector<uint8_t> visited(n, 0);
  auto terminal = [&](int v) { return adjacency[v].size() != 2; };
  auto follow = [&](int start, int first) {
    CellPolyline polyline;
    polyline.points.push_back(vertex[start]);
    int previous = start;
    int current = first;
    while (true) {
      polyline.points.push_back(vertex[current]);
      if (terminal(current) || current == start) break;
      visited[current] = 1;
      const int next =
          adjacency[current][0] == previous ? adjacency[current][1] : adjacency[current][0];
      previous = current;
      current = next;
    }
    if (polyline.points.size() >= 2 && polyline.points.front() == polyline.points.back()) {
      polyline.points.pop_back();
      polyline.closed = polyline.points.size() >= 3;
    }
    out.push_back(std::move(polyline));
  };
  for (int v = 0; v < n; ++v) {
    if (!terminal(v) || removed[v]) continue;
    if (adjacency[v].empty()) {
      out.push_back(CellPolyline{{vertex[v]}});
      continue;
    }
    for (const int u : adjacency[v]) {
      if (terminal(u)) {
        if (v < u) out.push_back(CellPolyline{{vertex[v], vertex[u]}});
      } else if (!visited[u]) {
        follow(v, u);
      }
    }
  }
  for (int v = 0; v < n; ++v) {
    if (!terminal(v) && !visited[v] && !adjacency[v].empty()) {
      visited[v] = 1;
      follow(v, adjacency[v][0]);
    }
  }
  return out;
}

}  // namespace

double Vectorizer::EpsilonFor(double resolution) const {
  return options_.epsilon > 0.0 ? options_.epsilon : DefaultEpsilon(resolution);
}

StatusOr<VectorMap> Vectorizer::Vectorize(const grid::OccupancyGrid& grid) const {
  return VectorizeTile(grid, FullRect(grid));
}

StatusOr<VectorMap> Vectorizer::VectorizeTile(const grid::OccupancyGrid& grid,
                                              const CellRect& rect) const {
  const double resolution = grid.resolution();
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    return InvalidArgumentError("vectorize: grid resolution must be positive and finite");
  }
  const double epsilon = EpsilonFor(resolution);
  if (!std::isfinite(epsilon) || epsilon < resolution * std::numbers::sqrt2 / 2.0 * (1 - 1e-12)) {
    return InvalidArgumentError("vectorize: epsilon " + std::to_string(epsilon) +
                                " m is below resolution * sqrt(2) / 2");
  }
  if (rect.x0 < 0 || rect.y0 < 0 || rect.width < 0 || rect.height < 0 ||
      rect.x0 + rect.width > grid.width() || rect.y0 + rect.height > grid.height()) {
    return InvalidArgumentError("vectorize: tile rectangle is not inside the " +
                                std::to_string(grid.width()) + " x " +
                                std::to_string(grid.height()) + " grid");
  }
  const double eps_cells = epsilon / resolution;
  VectorMap map;
  map.frame_id = options_.frame_id;
  map.resolution = resolution;
  map.epsilon = epsilon;
  if (rect.empty()) return map;

  const int margin = static_cast<int>(std::ceil(eps_cells)) + 3;
  const Delimitation delimitation(grid, rect, margin, options_.thresholds);
  std::vector<CellPolyline> polylines;
  if (options_.method == VectorizeMethod::kPaper) {
    polylines = PaperVectorize(delimitation, rect, eps_cells);
  } else {
    DefaultTileVectorizer tile(delimitation, rect, eps_cells);
    polylines = tile.Run();
  }
  const CellFrame frame(grid);
  map.obstacles.reserve(polylines.size());
  for (const CellPolyline& polyline : polylines) {
    Polyline out;
    out.closed = polyline.closed;
    out.points.reserve(polyline.points.size());
    for (const Point2& p : polyline.points) out.points.push_back(frame.ToMap(p));
    map.obstacles.push_back(std::move(out));
  }
  if (options_.extract_free_space) {
    const double free_eps = options_.free_epsilon > 0.0 ? options_.free_epsilon : epsilon;
    for (const auto& polygon :
         ExtractFreeSpace(grid, rect, options_.thresholds, free_eps / resolution)) {
      FreePolygon out;
      for (const Point2& p : polygon.outer) out.outer.push_back(frame.ToMap(p));
      for (const auto& hole : polygon.holes) {
        auto& ring = out.holes.emplace_back();
        for (const Point2& p : hole) ring.push_back(frame.ToMap(p));
      }
      map.free_space.push_back(std::move(out));
    }
  }
  return map;
}

}  // namespace fleetmap::vector_map
