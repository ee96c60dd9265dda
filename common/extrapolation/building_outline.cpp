#include "common/extrapolation/building_outline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace fleetmap::extrapolation {
namespace {

enum CellKind : int8_t { kUnknownCell = 0, kFreeCell = 1, kOccupiedCell = 2 };

// Continuations that pass through the doorway this far behind the door line (metres) are the
// door's own wall (as in DoorSpace).
constexpr double kDoorwayDepth = 1.0;
// Candidate principal angles are this far apart (radians, 0.5 degree).
constexpr double kAngleStep = std::numbers::pi / 360.0;

// Lattice centres (cell units) of the occupied cells with a free 4-neighbour: the seen wall faces.
std::vector<Vector2> FaceCells(const grid::OccupancyGrid& map) {
  std::vector<Vector2> faces;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (map.StateAt(x, y) != grid::CellState::kOccupied) continue;
      const int n[4][2] = {{x + 1, y}, {x - 1, y}, {x, y + 1}, {x, y - 1}};
      for (const auto& c : n) {
        if (map.Contains(c[0], c[1]) && map.StateAt(c[0], c[1]) == grid::CellState::kFree) {
          faces.emplace_back(x + 0.5, y + 0.5);
          break;
        }
      }
    }
  }
  return faces;
}

// The angle in [0, pi/2) at which the faces, projected on both rotated axes, pile up in the
// fewest one-cell bins (the sum of squared bin counts is largest): walls line up along it.
double PrincipalAngle(const std::vector<Vector2>& faces) {
  if (faces.size() < 2) return 0.0;
  double best_angle = 0.0, best_score = -1.0;
  std::vector<int64_t> bins;
  const int steps = static_cast<int>(std::lround(0.5 * std::numbers::pi / kAngleStep));
  for (int s = 0; s < steps; ++s) {
    const double a = s * kAngleStep;
    const double c = std::cos(a), sn = std::sin(a);
    double score = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vector2& f : faces) {
        const double p = axis == 0 ? c * f.x() + sn * f.y() : -sn * f.x() + c * f.y();
        lo = std::min(lo, p), hi = std::max(hi, p);
      }
      bins.assign(static_cast<size_t>(hi - lo) + 2, 0);
      for (const Vector2& f : faces) {
        const double p = axis == 0 ? c * f.x() + sn * f.y() : -sn * f.x() + c * f.y();
        ++bins[static_cast<size_t>(p - lo)];
      }
      for (int64_t b : bins) score += static_cast<double>(b) * static_cast<double>(b);
    }
    // Strictly better only: an axis-aligned map keeps the grid's axes exactly.
    if (score > best_score) best_score = score, best_angle = a;
  }
  return best_angle;
}

}  // namespace

BuildingOutline::BuildingOutline(const grid::OccupancyGrid& map,
                                 const BuildingOutlineOptions& options)
    : map_(map) {
  angle_ = PrincipalAngle(FaceCells(map));
  cos_ = std::cos(angle_), sin_ = std::sin(angle_);
  // The rotated grid: the map's lattice rectangle in rotated coordinates, one-cell cells.
  double umin = std::numeric_limits<double>::infinity(), umax = -umin, vmin = umin, vmax = -umin;
  for (const auto& [qx, qy] :
       {std::pair{0.0, 0.0}, std::pair{1.0 * map.width(), 0.0}, std::pair{0.0, 1.0 * map.height()},
        std::pair{1.0 * map.width(), 1.0 * map.height()}}) {
    const double u = cos_ * qx + sin_ * qy, v = -sin_ * qx + cos_ * qy;
    umin = std::min(umin, u), umax = std::max(umax, u);
    vmin = std::min(vmin, v), vmax = std::max(vmax, v);
  }
  u0_ = std::floor(umin + 1e-9), v0_ = std::floor(vmin + 1e-9);
  width_ = std::max(1, static_cast<int>(std::ceil(umax - u0_ - 1e-9)));
  height_ = std::max(1, static_cast<int>(std::ceil(vmax - v0_ - 1e-9)));
  const int w = width_, h = height_;
  const auto at = [w](int i, int j) { return static_cast<size_t>(j) * w + i; };
  std::vector<int8_t> state(static_cast<size_t>(w) * h, kUnknownCell);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double u = u0_ + i + 0.5, v = v0_ + j + 0.5;
      const int x = static_cast<int>(std::floor(cos_ * u - sin_ * v));
      const int y = static_cast<int>(std::floor(sin_ * u + cos_ * v));
      if (!map.Contains(x, y)) continue;
      const grid::CellState s = map.StateAt(x, y);
      state[at(i, j)] = s == grid::CellState::kFree       ? kFreeCell
                        : s == grid::CellState::kOccupied ? kOccupiedCell
                                                          : kUnknownCell;
    }
  }
  // The extreme observed free cells: a bound no free cell lies beyond.
  int free_min_u = w, free_max_u = -1, free_min_v = h, free_max_v = -1;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (state[at(i, j)] != kFreeCell) continue;
      free_min_u = std::min(free_min_u, i), free_max_u = std::max(free_max_u, i);
      free_min_v = std::min(free_min_v, j), free_max_v = std::max(free_max_v, j);
    }
  }

  const double r = map.resolution();
  const int min_run = static_cast<int>(std::ceil(options.min_outer_wall / r - 1e-9));
  const int max_gap = std::max(0, static_cast<int>(std::ceil(options.max_face_gap / r)) - 1);
  const int max_free_gap = static_cast<int>(std::floor(options.continuation_gap / r + 1e-9));
  min_u_ = min_v_ = std::numeric_limits<int>::min();
  max_u_ = max_v_ = std::numeric_limits<int>::max();
  int outer_max_u = -1, outer_min_u = w, outer_max_v = -1, outer_min_v = h;
  // d: the face's normal from the free side into the wall (outward if the wall is outer).
  const int directions[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const auto& d : directions) {
    // Per cell: observed free space anywhere beyond it along d (one sweep from the far side).
    std::vector<uint8_t> beyond(state.size(), 0);
    for (int line = 0; line < (d[1] != 0 ? w : h); ++line) {
      uint8_t seen = 0;
      const int steps = d[1] != 0 ? h : w;
      for (int n = 0; n < steps; ++n) {
        const int k = (d[0] + d[1] > 0) ? steps - 1 - n : n;  // from the far side back
        const int i = d[1] != 0 ? line : k, j = d[1] != 0 ? k : line;
        beyond[at(i, j)] = seen;
        seen = seen || state[at(i, j)] == kFreeCell;
      }
    }
    const bool along_u = d[1] != 0;  // the face runs along u (on a row) when d is along v
    const int lines = along_u ? h : w;
    const int length = along_u ? w : h;
    for (int line = 0; line < lines; ++line) {
      const auto cell = [&](int k) { return along_u ? std::pair{k, line} : std::pair{line, k}; };
      const auto inside = [&](int i, int j) { return i >= 0 && j >= 0 && i < w && j < h; };
      const auto is_face = [&](int k) {
        const auto [i, j] = cell(k);
        const int fi = i - d[0], fj = j - d[1];
        return state[at(i, j)] == kOccupiedCell && inside(fi, fj) && state[at(fi, fj)] == kFreeCell;
      };
      // Observed free space anywhere behind the face cell, along d.
      const auto free_behind = [&](int k) {
        const auto [i, j] = cell(k);
        return beyond[at(i, j)] != 0;
      };
      int k = 0;
      while (k < length) {
        if (!is_face(k)) {
          ++k;
          continue;
        }
        const int first = k;
        int last = k, faces = 0, outer = 0;
        for (int m = k; m < length; ++m) {
          const auto [i, j] = cell(m);
          if (is_face(m)) {
            last = m;
            ++faces;
            outer += !free_behind(m);
          } else if (state[at(i, j)] == kFreeCell || m - last > max_gap) {
            break;
          }
        }
        k = last + 1;
        if (last - first + 1 < min_run || outer < options.min_outer_share * faces) continue;
        Line wall;
        wall.along_u = along_u;
        wall.line = line;
        wall.outward = along_u ? d[1] : d[0];
        wall.lo = first, wall.hi = last;
        // Continued from both ends through unknown and occupied cells, up to observed free space
        // (an opening when that is close to the wall's end: that side is not continued).
        for (const int step : {-1, 1}) {
          int end = step < 0 ? first : last;
          for (int m = end + step, n = 1;; m += step, ++n) {
            if (m < 0 || m >= length) {
              end = m - step;
              break;
            }
            const auto [i, j] = cell(m);
            if (state[at(i, j)] == kFreeCell) {
              if (n > max_free_gap) end = m - step;
              break;
            }
          }
          (step < 0 ? wall.lo : wall.hi) = end;
        }
        lines_.push_back(wall);
        if (along_u) {
          if (wall.outward > 0) outer_max_v = std::max(outer_max_v, line);
          if (wall.outward < 0) outer_min_v = std::min(outer_min_v, line);
        } else {
          if (wall.outward > 0) outer_max_u = std::max(outer_max_u, line);
          if (wall.outward < 0) outer_min_u = std::min(outer_min_u, line);
        }
      }
    }
  }
  // The outline: the outermost outer wall in each direction, unless free space was seen beyond it.
  if (outer_max_u >= 0 && free_max_u < outer_max_u) max_u_ = outer_max_u;
  if (outer_min_u < w && free_min_u > outer_min_u) min_u_ = outer_min_u;
  if (outer_max_v >= 0 && free_max_v < outer_max_v) max_v_ = outer_max_v;
  if (outer_min_v < h && free_min_v > outer_min_v) min_v_ = outer_min_v;
}

void BuildingOutline::ToRotated(double qx, double qy, int* i, int* j) const {
  *i = static_cast<int>(std::floor(cos_ * qx + sin_ * qy - u0_));
  *j = static_cast<int>(std::floor(-sin_ * qx + cos_ * qy - v0_));
}

std::vector<uint8_t> BuildingOutline::AllowedFor(const scene::DoorEntity& door,
                                                 const Vector2& opening) const {
  const double r = map_.resolution();
  const Eigen::Isometry2d lattice_from_map = map_.origin().ToTransform().inverse();
  const auto lattice = [&](const Point2& p) -> Vector2 { return lattice_from_map * p / r; };
  const Vector2 opening_lattice = lattice_from_map.linear() * opening;
  const double w = door.width();
  const Vector2 along = (door.latch - door.hinge) / w;
  const Vector2 along_lattice = lattice_from_map.linear() * along;
  const Vector2 hinge = lattice(door.hinge);
  // The doorway, sampled every half cell: up to kDoorwayDepth behind the door line.
  std::vector<std::pair<int, int>> doorway;
  for (double s = 0.0; s <= w / r + 1e-9; s += 0.5) {
    for (double t = -1.5; t <= kDoorwayDepth / r + 1e-9; t += 0.5) {
      const Vector2 q = hinge + s * along_lattice + t * opening_lattice;
      int i = 0, j = 0;
      ToRotated(q.x(), q.y(), &i, &j);
      doorway.emplace_back(i, j);
    }
  }
  const auto on_barrier = [](const Line& l, int i, int j) {
    const int across = l.along_u ? j : i, a = l.along_u ? i : j;
    return (across == l.line || across == l.line + l.outward) && a >= l.lo && a <= l.hi;
  };
  std::vector<uint8_t> barrier(static_cast<size_t>(width_) * height_, 0);
  for (const Line& l : lines_) {
    bool own_wall = false;
    for (const auto& [i, j] : doorway) own_wall = own_wall || on_barrier(l, i, j);
    if (own_wall) continue;
    for (int a = l.lo; a <= l.hi; ++a) {
      for (const int across : {l.line, l.line + l.outward}) {
        const int i = l.along_u ? a : across, j = l.along_u ? across : a;
        if (i >= 0 && j >= 0 && i < width_ && j < height_) {
          barrier[static_cast<size_t>(j) * width_ + i] = 1;
        }
      }
    }
  }
  // A bound the doorway lies beyond is not this room's outline.
  int min_u = min_u_, max_u = max_u_, min_v = min_v_, max_v = max_v_;
  for (const auto& [i, j] : doorway) {
    if (i < min_u) min_u = std::numeric_limits<int>::min();
    if (i > max_u) max_u = std::numeric_limits<int>::max();
    if (j < min_v) min_v = std::numeric_limits<int>::min();
    if (j > max_v) max_v = std::numeric_limits<int>::max();
  }
  std::vector<uint8_t> allowed(static_cast<size_t>(map_.cell_count()), 0);
  for (int y = 0; y < map_.height(); ++y) {
    for (int x = 0; x < map_.width(); ++x) {
      int i = 0, j = 0;
      ToRotated(x + 0.5, y + 0.5, &i, &j);
      const bool in_outline = i > min_u && i < max_u && j > min_v && j < max_v;
      const bool on_line = i >= 0 && j >= 0 && i < width_ && j < height_ &&
                           barrier[static_cast<size_t>(j) * width_ + i];
      allowed[static_cast<size_t>(y) * map_.width() + x] = in_outline && !on_line;
    }
  }
  return allowed;
}

}  // namespace fleetmap::extrapolation
