#include "common/extrapolation/place_partition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fleetmap::extrapolation {
namespace {

// The segment a-b in cell units of the map's lattice (cell (x, y) spans [x, x + 1) x [y, y + 1)),
// clipped to the map grown by `margin` cells; nullopt if it misses it. Bounds the work a huge
// (garbage) segment can cause.
std::optional<std::pair<Point2, Point2>> ClipToMap(const grid::OccupancyGrid& map, const Point2& a,
                                                   const Point2& b, double margin) {
  const Transform2 grid_from_map = map.origin().ToTransform().inverse();
  const Point2 p = grid_from_map * a / map.resolution();
  const Vector2 d = grid_from_map * b / map.resolution() - p;
  double t0 = 0.0, t1 = 1.0;
  const double lo[2] = {-margin, -margin};
  const double hi[2] = {map.width() + margin, map.height() + margin};
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) < 1e-12) {
      if (p[axis] < lo[axis] || p[axis] > hi[axis]) return std::nullopt;
      continue;
    }
    double ta = (lo[axis] - p[axis]) / d[axis], tb = (hi[axis] - p[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return std::make_pair(Point2(p + t0 * d), Point2(p + t1 * d));
}

// The cells of the segments, sampled every quarter cell, dilated by one cell.
std::vector<uint8_t> CutMask(const grid::OccupancyGrid& map, const std::vector<PlaceCut>& cuts) {
  const int w = map.width(), h = map.height();
  std::vector<uint8_t> cut(static_cast<size_t>(w) * h, 0);
  for (const PlaceCut& c : cuts) {
    const auto clipped = ClipToMap(map, c.a, c.b, 2.0);
    if (!clipped) continue;
    const auto& [ga, gb] = *clipped;
    const auto steps =
        std::max<int64_t>(1, static_cast<int64_t>(std::ceil((gb - ga).norm() / 0.25)));
    for (int64_t i = 0; i <= steps; ++i) {
      const Point2 g = ga + (static_cast<double>(i) / steps) * (gb - ga);
      const auto cx = static_cast<int64_t>(std::floor(g.x()));
      const auto cy = static_cast<int64_t>(std::floor(g.y()));
      for (int64_t y = cy - 1; y <= cy + 1; ++y) {
        for (int64_t x = cx - 1; x <= cx + 1; ++x) {
          if (x >= 0 && y >= 0 && x < w && y < h) cut[static_cast<size_t>(y) * w + x] = 1;
        }
      }
    }
  }
  return cut;
}

}  // namespace

PlacePartition PartitionPlaces(const grid::OccupancyGrid& map, const std::vector<uint8_t>& free,
                               const std::vector<PlaceCut>& cuts, int64_t min_place_cells) {
  const int w = map.width(), h = map.height();
  const size_t n = static_cast<size_t>(w) * h;
  PlacePartition out;
  out.width = w;
  out.height = h;
  out.labels.assign(n, -1);
  const std::vector<uint8_t> cut = CutMask(map, cuts);
  auto neighbours = [&](size_t i, auto&& visit) {
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    if (x + 1 < w) visit(i + 1);
    if (x > 0) visit(i - 1);
    if (y + 1 < h) visit(i + w);
    if (y > 0) visit(i - w);
  };

  // Cores: 4-connected components of the free cells off the cuts, in row-major order.
  std::vector<int32_t> core(n, -1);
  std::vector<int64_t> core_size;
  std::vector<size_t> stack;
  for (size_t s = 0; s < n; ++s) {
    if (!free[s] || cut[s] || core[s] >= 0) continue;
    const auto id = static_cast<int32_t>(core_size.size());
    int64_t size = 0;
    core[s] = id;
    stack.push_back(s);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      ++size;
      neighbours(i, [&](size_t j) {
        if (free[j] && !cut[j] && core[j] < 0) {
          core[j] = id;
          stack.push_back(j);
        }
      });
    }
    core_size.push_back(size);
  }
  if (core_size.empty()) return out;

  // Places: the large cores (or the largest one), renumbered in the same order.
  std::vector<int32_t> place_of_core(core_size.size(), -1);
  for (size_t c = 0; c < core_size.size(); ++c) {
    if (core_size[c] >= min_place_cells) place_of_core[c] = out.place_count++;
  }
  if (out.place_count == 0) {
    const auto largest = std::max_element(core_size.begin(), core_size.end()) - core_size.begin();
    place_of_core[largest] = out.place_count++;
  }
  std::vector<size_t> frontier;
  for (size_t i = 0; i < n; ++i) {
    if (core[i] >= 0 && place_of_core[core[i]] >= 0) {
      out.labels[i] = place_of_core[core[i]];
      frontier.push_back(i);
    }
  }

  // Every other free cell joins the nearest place (breadth first, one ring at a time; a cell
  // reached from two places in the same ring takes the lower one).
  constexpr int32_t kNone = std::numeric_limits<int32_t>::max();
  std::vector<int32_t>& pending = core;  // the cores are done with: reuse their memory
  std::fill(pending.begin(), pending.end(), kNone);
  std::vector<size_t> next;
  while (!frontier.empty()) {
    next.clear();
    for (size_t i : frontier) {
      neighbours(i, [&](size_t j) {
        if (!free[j] || out.labels[j] >= 0) return;
        if (pending[j] == kNone) next.push_back(j);
        pending[j] = std::min(pending[j], out.labels[i]);
      });
    }
    for (size_t j : next) out.labels[j] = pending[j];
    frontier.swap(next);
  }
  return out;
}

std::optional<int32_t> PlaceBeside(const grid::OccupancyGrid& map, const PlacePartition& places,
                                   const Point2& a, const Point2& b, const Vector2& side,
                                   double depth) {
  if (side.norm() < 1e-9) return std::nullopt;
  const double r = map.resolution();
  const auto depth_steps = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(depth / r)));
  const auto clipped = ClipToMap(map, a, b, depth_steps + 2.0);
  if (!clipped) return std::nullopt;
  const Transform2 map_from_grid = map.origin().ToTransform();
  const Point2 ca = map_from_grid * (clipped->first * r);
  const Point2 cb = map_from_grid * (clipped->second * r);
  const Vector2 s = side.normalized();
  std::map<int32_t, int64_t> votes;
  const auto along_steps =
      std::max<int64_t>(1, static_cast<int64_t>(std::ceil((cb - ca).norm() / r)));
  for (int64_t i = 0; i <= along_steps; ++i) {
    const Point2 on_line = ca + (static_cast<double>(i) / along_steps) * (cb - ca);
    for (int64_t k = 1; k <= depth_steps; ++k) {
      const std::optional<grid::CellIndex> cell = map.CellAt(on_line + (k * r) * s);
      if (!cell) continue;
      const int32_t label = places.Label(cell->x, cell->y);
      if (label >= 0) ++votes[label];
    }
  }
  std::optional<int32_t> best;
  int64_t best_votes = 0;
  for (const auto& [label, count] : votes) {  // ascending labels: ties keep the lower
    if (count > best_votes) {
      best = label;
      best_votes = count;
    }
  }
  return best;
}

std::optional<int32_t> NearestPlace(const grid::OccupancyGrid& map, const PlacePartition& places,
                                    const Point2& p) {
  std::optional<int32_t> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int y = 0; y < places.height; ++y) {
    for (int x = 0; x < places.width; ++x) {
      const int32_t label = places.Label(x, y);
      if (label < 0) continue;
      const double d = (map.CellCenter(x, y) - p).squaredNorm();
      if (d < best_distance) {
        best_distance = d;
        best = label;
      }
    }
  }
  return best;
}

}  // namespace fleetmap::extrapolation
