#include "common/sim/frontier_planner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <optional>

#include "common/grid/line_iterator.hpp"

namespace fleetmap::sim {
namespace {}  // namespace

StatusOr<FrontierPlanner> FrontierPlanner::Create(const FrontierOptions& options) {
  if (!(options.inflation_radius > 0.0) || !std::isfinite(options.inflation_radius)) {
    return InvalidArgumentError("frontier inflation_radius must be > 0");
  }
  if (!(options.blacklist_radius >= 0.0) || !std::isfinite(options.blacklist_radius)) {
    return InvalidArgumentError("frontier blacklist_radius must be >= 0");
  }
  if (options.min_frontier_blocks < 1) {
    return InvalidArgumentError("frontier min_frontier_blocks must be >= 1");
  }
  return FrontierPlanner(options);
}

void FrontierPlanner::Classify(const OccupancyMapper& map) {
  const int bs = map.block_size();
  if (bw_ != map.blocks_x() || bh_ != map.blocks_y()) {
    bw_ = map.blocks_x();
    bh_ = map.blocks_y();
    blacklist_.assign(static_cast<size_t>(bw_) * bh_, 0);
  }
  block_m_ = bs * map.resolution();
  const size_t n = static_cast<size_t>(bw_) * bh_;
  state_.assign(n, kUnknownBlock);
  traversable_.assign(n, 0);
  near_frontier_.assign(n, 0);
  start_region_.assign(n, 0);
  const int half = (bs * bs + 1) / 2;
  for (int by = 0; by < bh_; ++by) {
    for (int bx = 0; bx < bw_; ++bx) {
      const size_t i = static_cast<size_t>(by) * bw_ + bx;
      if (map.BlockOccupied(bx, by) > 0) {
        state_[i] = kOccupiedBlock;
      } else if (map.BlockFree(bx, by) >= half) {
        state_[i] = kFreeBlock;
        traversable_[i] = 1;
      }
    }
  }
  // Inflate occupied blocks.
  const double r = options_.inflation_radius / block_m_;
  const int reach = static_cast<int>(std::ceil(r));
  for (int by = 0; by < bh_; ++by) {
    for (int bx = 0; bx < bw_; ++bx) {
      if (state_[static_cast<size_t>(by) * bw_ + bx] != kOccupiedBlock) continue;
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          const int x = bx + dx;
          const int y = by + dy;
          if (x < 0 || y < 0 || x >= bw_ || y >= bh_ || dx * dx + dy * dy > r * r) continue;
          traversable_[static_cast<size_t>(y) * bw_ + x] = 0;
        }
      }
    }
  }
  // Frontier blocks, then the blocks within two blocks of one (Chebyshev).
  std::vector<uint8_t> frontier(n, 0);
  for (int by = 1; by + 1 < bh_; ++by) {
    for (int bx = 1; bx + 1 < bw_; ++bx) {
      const size_t i = static_cast<size_t>(by) * bw_ + bx;
      if (state_[i] != kFreeBlock) continue;
      frontier[i] = state_[i - 1] == kUnknownBlock || state_[i + 1] == kUnknownBlock ||
                    state_[i - bw_] == kUnknownBlock || state_[i + bw_] == kUnknownBlock;
    }
  }
  for (int by = 1; by + 1 < bh_; ++by) {
    for (int bx = 1; bx + 1 < bw_; ++bx) {
      const size_t i = static_cast<size_t>(by) * bw_ + bx;
      if (!frontier[i]) continue;
      int neighbours = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) neighbours += frontier[i + dy * bw_ + dx];
      }
      if (neighbours < options_.min_frontier_blocks) continue;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = bx + dx;
          const int y = by + dy;
          if (x >= 0 && y >= 0 && x < bw_ && y < bh_) {
            near_frontier_[static_cast<size_t>(y) * bw_ + x] = 1;
          }
        }
      }
    }
  }
}

bool FrontierPlanner::LineOfSight(int x0, int y0, int x1, int y1) const {
  const auto index = [this](int x, int y) { return static_cast<size_t>(y) * bw_ + x; };
  std::optional<grid::CellIndex> previous;
  for (const grid::CellIndex cell : grid::GridLine({x0, y0}, {x1, y1})) {
    // Moving diagonally, both side blocks must be passable too (no corner cutting).
    if (previous && cell.x != previous->x && cell.y != previous->y &&
        (!Passable(index(cell.x, previous->y)) || !Passable(index(previous->x, cell.y)))) {
      return false;
    }
    if (!Passable(index(cell.x, cell.y))) return false;
    previous = cell;
  }
  return true;
}

std::vector<Point2> FrontierPlanner::Plan(const OccupancyMapper& map, const Point2& robot) {
  Classify(map);
  const double res = map.resolution();
  const int sx = std::clamp(
      static_cast<int>(std::floor((robot.x() - map.origin().x) / res)) / map.block_size(), 0,
      bw_ - 1);
  const int sy = std::clamp(
      static_cast<int>(std::floor((robot.y() - map.origin().y) / res)) / map.block_size(), 0,
      bh_ - 1);
  const size_t n = static_cast<size_t>(bw_) * bh_;
  std::vector<int32_t> parent(n, -1);
  std::vector<int32_t> depth(n, -1);
  const size_t start = static_cast<size_t>(sy) * bw_ + sx;
  std::deque<size_t> queue = {start};
  depth[start] = 0;
  parent[start] = static_cast<int32_t>(start);
  start_region_[start] = 1;
  int64_t goal = -1;
  const int dxs[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  const int dys[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!queue.empty()) {
    const size_t i = queue.front();
    queue.pop_front();
    // The robot's own block is never the goal: it is there already, and looking did not help.
    if (i != start && traversable_[i] && near_frontier_[i] && !blacklist_[i]) {
      goal = static_cast<int64_t>(i);
      break;
    }
    const int x = static_cast<int>(i % bw_);
    const int y = static_cast<int>(i / bw_);
    for (int k = 0; k < 8; ++k) {
      const int nx = x + dxs[k];
      const int ny = y + dys[k];
      if (nx < 0 || ny < 0 || nx >= bw_ || ny >= bh_) continue;
      const size_t j = static_cast<size_t>(ny) * bw_ + nx;
      if (depth[j] >= 0) continue;
      // Leaving an inflated region (the robot may stand in or next to one after new obstacles
      // appeared): free blocks are allowed until the search reaches a traversable block.
      const bool escape = start_region_[i] && state_[j] == kFreeBlock;
      if (!traversable_[j] && !escape) continue;
      if (k >= 4) {  // diagonal: no corner cutting
        const size_t side_a = static_cast<size_t>(y) * bw_ + nx;
        const size_t side_b = static_cast<size_t>(ny) * bw_ + x;
        if (state_[side_a] == kOccupiedBlock || state_[side_b] == kOccupiedBlock) continue;
      }
      if (escape && !traversable_[j]) start_region_[j] = 1;
      depth[j] = depth[i] + 1;
      parent[j] = static_cast<int32_t>(i);
      queue.push_back(j);
    }
  }
  if (goal < 0) return {};
  std::vector<size_t> cells;
  for (size_t i = static_cast<size_t>(goal); i != start; i = static_cast<size_t>(parent[i])) {
    cells.push_back(i);
  }
  cells.push_back(start);
  std::reverse(cells.begin(), cells.end());
  // String pulling: from each kept block, jump to the farthest block still in sight.
  auto centre = [&](size_t i) {
    return Point2(map.origin().x + (static_cast<double>(i % bw_) + 0.5) * block_m_,
                  map.origin().y + (static_cast<double>(i / bw_) + 0.5) * block_m_);
  };
  std::vector<Point2> path = {robot};
  size_t from = 0;
  while (from + 1 < cells.size()) {
    size_t to = from + 1;
    while (to + 1 < cells.size() &&
           LineOfSight(static_cast<int>(cells[from] % bw_), static_cast<int>(cells[from] / bw_),
                       static_cast<int>(cells[to + 1] % bw_),
                       static_cast<int>(cells[to + 1] / bw_))) {
      ++to;
    }
    path.push_back(centre(cells[to]));
    from = to;
  }
  return path;
}

void FrontierPlanner::Blacklist(const OccupancyMapper& map, const Point2& goal) {
  if (bw_ != map.blocks_x() || bh_ != map.blocks_y()) Classify(map);
  block_m_ = map.block_size() * map.resolution();
  const double r = options_.blacklist_radius / block_m_;
  const int reach = static_cast<int>(std::ceil(r));
  const int gx = static_cast<int>(std::floor((goal.x() - map.origin().x) / block_m_));
  const int gy = static_cast<int>(std::floor((goal.y() - map.origin().y) / block_m_));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const int x = gx + dx;
      const int y = gy + dy;
      if (x < 0 || y < 0 || x >= bw_ || y >= bh_ || dx * dx + dy * dy > r * r) continue;
      blacklist_[static_cast<size_t>(y) * bw_ + x] = 1;
    }
  }
}

}  // namespace fleetmap::sim
