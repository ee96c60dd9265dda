#include "common/route_graph/grid_planner.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace fleetmap::route_graph {
namespace {

constexpr int kStepX[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kStepY[8] = {0, 0, 1, -1, 1, -1, 1, -1};

}  // namespace

GridPlanner::GridPlanner(const ClearanceMap& clearance, double required)
    : clearance_(clearance),
      required_(required),
      component_(static_cast<size_t>(clearance.width()) * clearance.height(), -1) {
  int next = 0;
  std::vector<grid::CellIndex> stack;
  for (int y = 0; y < clearance.height(); ++y) {
    for (int x = 0; x < clearance.width(); ++x) {
      if (!Traversable({x, y}) || component_[Index({x, y})] >= 0) continue;
      component_[Index({x, y})] = next;
      stack.push_back({x, y});
      while (!stack.empty()) {
        const grid::CellIndex cell = stack.back();
        stack.pop_back();
        for (int k = 0; k < 8; ++k) {
          const grid::CellIndex n{cell.x + kStepX[k], cell.y + kStepY[k]};
          if (!Traversable(n) || component_[Index(n)] >= 0) continue;
          component_[Index(n)] = next;
          stack.push_back(n);
        }
      }
      ++next;
    }
  }
}

bool GridPlanner::Traversable(const grid::CellIndex& cell) const {
  return clearance_.Contains(cell.x, cell.y) && clearance_.at(cell.x, cell.y) >= required_;
}

int GridPlanner::Component(const grid::CellIndex& cell) const {
  return clearance_.Contains(cell.x, cell.y) ? component_[Index(cell)] : -1;
}

std::vector<grid::CellIndex> GridPlanner::TraversableCells() const {
  std::vector<grid::CellIndex> cells;
  for (int y = 0; y < clearance_.height(); ++y) {
    for (int x = 0; x < clearance_.width(); ++x) {
      if (Traversable({x, y})) cells.push_back({x, y});
    }
  }
  return cells;
}

std::optional<double> GridPlanner::PathLength(const grid::CellIndex& from,
                                              const grid::CellIndex& to) const {
  if (!Traversable(from) || !Traversable(to) || Component(from) != Component(to)) {
    return std::nullopt;
  }
  const double kInfinity = std::numeric_limits<double>::infinity();
  auto heuristic = [&to](const grid::CellIndex& cell) {
    const double dx = std::abs(cell.x - to.x);
    const double dy = std::abs(cell.y - to.y);
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
  };
  std::vector<double> cost(component_.size(), kInfinity);
  using Entry = std::pair<double, size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  cost[Index(from)] = 0.0;
  open.push({heuristic(from), Index(from)});
  const size_t goal = Index(to);
  const int width = clearance_.width();
  while (!open.empty()) {
    const auto [f, index] = open.top();
    open.pop();
    if (index == goal) return cost[goal] * clearance_.resolution();
    const grid::CellIndex cell{static_cast<int>(index % width), static_cast<int>(index / width)};
    if (f > cost[index] + heuristic(cell) + 1e-9) continue;
    for (int k = 0; k < 8; ++k) {
      const grid::CellIndex n{cell.x + kStepX[k], cell.y + kStepY[k]};
      if (!Traversable(n)) continue;
      const double step = k < 4 ? 1.0 : std::sqrt(2.0);
      const size_t n_index = Index(n);
      if (cost[index] + step >= cost[n_index]) continue;
      cost[n_index] = cost[index] + step;
      open.push({cost[n_index] + heuristic(n), n_index});
    }
  }
  return std::nullopt;
}

}  // namespace fleetmap::route_graph
