#include "common/grid/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>

#include "common/core/check.hpp"

namespace fleetmap::grid {

bool SameResolution(double a, double b) {
  return std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b));
}

CellState StateOf(int8_t value, const StateThresholds& thresholds) {
  if (value < 0 || value > 100) return CellState::kUnknown;
  const double probability = value / 100.0;
  if (probability > thresholds.occupied) return CellState::kOccupied;
  if (probability < thresholds.free) return CellState::kFree;
  return CellState::kUnknown;
}

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Pose2 origin, int8_t fill)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      data_(static_cast<size_t>(width) * static_cast<size_t>(height), fill) {
  FLEETMAP_CHECK(width >= 0 && height >= 0 && resolution > 0.0);
}

Point2 OccupancyGrid::CellCenter(int x, int y) const {
  const Point2 in_grid((x + 0.5) * resolution_, (y + 0.5) * resolution_);
  return origin_.ToTransform() * in_grid;
}

std::optional<CellIndex> OccupancyGrid::CellAt(const Point2& map_point) const {
  const Point2 in_grid = origin_.ToTransform().inverse() * map_point;
  const int x = static_cast<int>(std::floor(in_grid.x() / resolution_));
  const int y = static_cast<int>(std::floor(in_grid.y() / resolution_));
  if (!Contains(x, y)) return std::nullopt;
  return CellIndex{x, y};
}

StateCounts OccupancyGrid::CountStates(const StateThresholds& thresholds) const {
  StateCounts counts;
  for (const int8_t value : data_) {
    switch (StateOf(value, thresholds)) {
      case CellState::kOccupied:
        ++counts.occupied;
        break;
      case CellState::kFree:
        ++counts.free;
        break;
      case CellState::kUnknown:
        ++counts.unknown;
        break;
    }
  }
  return counts;
}

}  // namespace fleetmap::grid
