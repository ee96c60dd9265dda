#include "common/extrapolation/door_space.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace fleetmap::extrapolation {
namespace {

enum CellKind : int8_t { kUnknownCell = 0, kFreeCell = 1, kOccupiedCell = 2 };

// Continuations that would pass through the doorway this far behind the door line (metres) are
// not walls of the room: they would cut the room off from its own door.
constexpr double kDoorwayDepth = 1.0;

// Keeps the cells of `mask` (row-major, width x height) 4-connected to a seed.
std::vector<uint8_t> ConnectedToSeeds(const std::vector<uint8_t>& mask, int width, int height,
                                      const std::vector<int>& seeds) {
  std::vector<uint8_t> reached(mask.size(), 0);
  std::deque<int> queue;
  for (int s : seeds) {
    if (s >= 0 && s < static_cast<int>(mask.size()) && mask[s] && !reached[s]) {
      reached[s] = 1;
      queue.push_back(s);
    }
  }
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    const int x = i % width, y = i / width;
    const int neighbours[4][2] = {{x + 1, y}, {x - 1, y}, {x, y + 1}, {x, y - 1}};
    for (const auto& n : neighbours) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= width || n[1] >= height) continue;
      const int j = n[1] * width + n[0];
      if (mask[j] && !reached[j]) {
        reached[j] = 1;
        queue.push_back(j);
      }
    }
  }
  return reached;
}

}  // namespace

DoorSpace::DoorSpace(const grid::OccupancyGrid& map, const scene::DoorEntity& door,
                     const Vector2& opening, const CellWindow& window,
                     const DoorSpaceOptions& options)
    : map_(map), door_(door), opening_(opening), window_(window), options_(options) {
  const double r = map.resolution();
  // The analysis looks beyond the window: a wall continued into it may start outside.
  const int margin = static_cast<int>(
      std::ceil(std::max(1.0, options.min_continued_wall + options.continuation_gap) / r));
  const int ax0 = window.x0 - margin, ay0 = window.y0 - margin;
  const int aw = window.width + 2 * margin, ah = window.height + 2 * margin;
  const auto at = [aw](int x, int y) { return static_cast<size_t>(y) * aw + x; };
  const auto inside = [aw, ah](int x, int y) { return x >= 0 && y >= 0 && x < aw && y < ah; };
  std::vector<int8_t> state(static_cast<size_t>(aw) * ah, kUnknownCell);
  for (int y = 0; y < ah; ++y) {
    for (int x = 0; x < aw; ++x) {
      if (!map.Contains(ax0 + x, ay0 + y)) continue;
      const grid::CellState s = map.StateAt(ax0 + x, ay0 + y);
      state[at(x, y)] = s == grid::CellState::kFree       ? kFreeCell
                        : s == grid::CellState::kOccupied ? kOccupiedCell
                                                          : kUnknownCell;
    }
  }
  const double w = door.width();
  const Vector2 along = (door.latch - door.hinge) / w;
  const Point2 centre = door.center();
  // (along the door from the hinge, depth behind the door line) of a cell of the analysis window.
  const auto door_frame = [&](int x, int y) {
    const Point2 c = map.CellCenter(ax0 + x, ay0 + y);
    return Vector2((c - door.hinge).dot(along), (c - centre).dot(opening));
  };
  // The opening through the door's wall: never wall, always passable.
  const double slab_depth = 2.0 * options.unseen_wall_thickness + r;
  const auto in_doorway = [&](int x, int y, double depth) {
    const Vector2 u = door_frame(x, y);
    return u.x() > 0.0 && u.x() < w && u.y() > -1.5 * r && u.y() < depth;
  };

  std::vector<uint8_t> wall(state.size(), 0);     // unknown cells taken as wall
  std::vector<uint8_t> barrier(state.size(), 0);  // continued walls
  const int thickness = static_cast<int>(std::lround(options.unseen_wall_thickness / r));
  const int max_gap = std::max(0, static_cast<int>(std::ceil(options.min_passage_width / r)) - 1);
  const int min_run = static_cast<int>(std::ceil(options.min_continued_wall / r - 1e-9));
  const int max_free_gap = static_cast<int>(std::floor(options.continuation_gap / r + 1e-9));
  // d: the face's normal, from the free side into the wall; the face runs along the other axis
  // (along x when d is along y).
  const int directions[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const auto& d : directions) {
    const bool ux = d[1] != 0;
    const int lines = ux ? ah : aw;  // faces along x lie on rows, along y on columns
    const int length = ux ? aw : ah;
    for (int line = 0; line < lines; ++line) {
      const auto cell = [&](int k) { return ux ? std::pair{k, line} : std::pair{line, k}; };
      // 1: a seen face; 2: an unknown cell in front of free space (a gap in a face); 0: neither.
      const auto kind = [&](int k) {
        const auto [x, y] = cell(k);
        const int fx = x - d[0], fy = y - d[1];
        if (!inside(fx, fy) || state[at(fx, fy)] != kFreeCell) return 0;
        if (in_doorway(x, y, slab_depth)) return 0;
        if (state[at(x, y)] == kOccupiedCell) return 1;
        return state[at(x, y)] == kUnknownCell ? 2 : 0;
      };
      int k = 0;
      while (k < length) {
        if (kind(k) != 1) {
          ++k;
          continue;
        }
        // A run from a seen face cell to the last seen one, across gaps of at most max_gap.
        const int first = k;
        int last = k;
        int j = k + 1;
        while (j < length) {
          const int kj = kind(j);
          if (kj == 1) {
            last = j++;
          } else if (kj == 2 && j - last <= max_gap) {
            ++j;
          } else {
            break;
          }
        }
        k = last + 1;
        // Thickness: behind every cell of the run (gaps included), up to the next free cell.
        for (int m = first; m <= last; ++m) {
          const auto [x, y] = cell(m);
          for (int t = 0; t <= thickness; ++t) {
            const int bx = x + t * d[0], by = y + t * d[1];
            if (!inside(bx, by) || state[at(bx, by)] == kFreeCell) break;
            if (state[at(bx, by)] == kUnknownCell && !in_doorway(bx, by, slab_depth)) {
              wall[at(bx, by)] = 1;
            }
          }
        }
        if (last - first + 1 < min_run) continue;
        // Continue the face's line from both ends through unknown and occupied cells.
        for (const int step : {-1, 1}) {
          std::vector<size_t> pending;
          bool keep = true;
          for (int m = (step < 0 ? first : last) + step, n = 1; m >= 0 && m < length;
               m += step, ++n) {
            const auto [x, y] = cell(m);
            if (in_doorway(x, y, kDoorwayDepth)) {
              keep = false;
              break;
            }
            if (state[at(x, y)] == kFreeCell) {
              keep = n > max_free_gap;
              break;
            }
            if (state[at(x, y)] == kUnknownCell) pending.push_back(at(x, y));
          }
          if (keep) {
            for (size_t i : pending) barrier[i] = 1;
          }
        }
      }
    }
  }

  const size_t n = static_cast<size_t>(window.width) * window.height;
  allowed_.assign(n, 0);
  doorway_.assign(n, 0);
  for (int y = 0; y < window.height; ++y) {
    for (int x = 0; x < window.width; ++x) {
      const size_t a = at(x + margin, y + margin);
      const size_t i = static_cast<size_t>(y) * window.width + x;
      allowed_[i] = state[a] == kUnknownCell && !wall[a] && !barrier[a] &&
                    door_frame(x + margin, y + margin).y() > options.wall_clearance;
      doorway_[i] = allowed_[i] && in_doorway(x + margin, y + margin, slab_depth);
    }
  }
  // Seeds: just behind the doorway.
  for (double s = 0.0; s <= w; s += 0.5 * r) {
    const Point2 p = door.hinge + s * along + (options.wall_clearance + r) * opening;
    const Point2 in_grid = map.origin().ToTransform().inverse() * p / r;
    const int x = static_cast<int>(std::floor(in_grid.x())) - window.x0;
    const int y = static_cast<int>(std::floor(in_grid.y())) - window.y0;
    if (x >= 0 && y >= 0 && x < window.width && y < window.height) {
      seeds_.push_back(y * window.width + x);
    }
  }
}

std::vector<uint8_t> DoorSpace::ReachableFromDoorway(const std::vector<uint8_t>& candidate) const {
  const int w = window_.width, h = window_.height;
  const std::vector<uint8_t> reached = ConnectedToSeeds(candidate, w, h, seeds_);
  // An opening by reconstruction with a disc of radius half the passage width: the core is where
  // the whole disc fits in the region; the core's part connected to the doorway, grown back by
  // the disc, is what a person could walk to. A passage narrower than the disc holds no core, so
  // what lies only beyond it is no longer reached.
  const double r = map_.resolution();
  const double radius = 0.5 * options_.min_passage_width;
  const int reach = static_cast<int>(std::ceil(radius / r));
  std::vector<std::pair<int, int>> disc;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (std::hypot(dx, dy) * r < radius - 1e-9) disc.emplace_back(dx, dy);
    }
  }
  std::vector<uint8_t> core(reached.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!reached[static_cast<size_t>(y) * w + x]) continue;
      bool fits = true;
      for (const auto& [dx, dy] : disc) {
        const int px = x + dx, py = y + dy;
        if (px < 0 || py < 0 || px >= w || py >= h || !reached[static_cast<size_t>(py) * w + px]) {
          fits = false;
          break;
        }
      }
      core[static_cast<size_t>(y) * w + x] = fits;
    }
  }
  // The core is followed from the doorway only: across a narrow gap in a thin wall, the discs of
  // the cores on both sides can meet, so the opened region alone would still connect them.
  std::vector<int> start;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!core[i]) continue;
      for (const auto& [dx, dy] : disc) {
        const int px = x + dx, py = y + dy;
        if (px >= 0 && py >= 0 && px < w && py < h && doorway_[static_cast<size_t>(py) * w + px]) {
          start.push_back(static_cast<int>(i));
          break;
        }
      }
    }
  }
  const std::vector<uint8_t> core_reached = ConnectedToSeeds(core, w, h, start);
  std::vector<uint8_t> opened(reached.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!core_reached[i]) continue;
      for (const auto& [dx, dy] : disc) {
        const int px = x + dx, py = y + dy;
        if (px >= 0 && py >= 0 && px < w && py < h) opened[static_cast<size_t>(py) * w + px] = 1;
      }
    }
  }
  for (size_t i = 0; i < opened.size(); ++i) {
    opened[i] = reached[i] && (opened[i] || doorway_[i]);
  }
  return ConnectedToSeeds(opened, w, h, seeds_);
}

std::vector<uint8_t> DoorSpace::ConnectedToDoorway(const std::vector<uint8_t>& mask) const {
  return ConnectedToSeeds(mask, window_.width, window_.height, seeds_);
}

}  // namespace fleetmap::extrapolation
