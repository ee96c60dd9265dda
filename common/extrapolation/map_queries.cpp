#include "common/extrapolation/map_queries.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/grid/line_iterator.hpp"

namespace fleetmap::extrapolation {

grid::CellState StateAtPoint(const grid::OccupancyGrid& map, const Point2& map_point) {
  const std::optional<grid::CellIndex> cell = map.CellAt(map_point);
  return cell ? map.StateAt(cell->x, cell->y) : grid::CellState::kUnknown;
}

bool LineOfSight(const grid::OccupancyGrid& map, const Point2& a, const Point2& b) {
  const Transform2 grid_from_map = map.origin().ToTransform().inverse();
  const Point2 ga = grid_from_map * a / map.resolution();
  const Point2 gb = grid_from_map * b / map.resolution();
  const grid::CellIndex from{static_cast<int>(std::floor(ga.x())),
                             static_cast<int>(std::floor(ga.y()))};
  const grid::CellIndex to{static_cast<int>(std::floor(gb.x())),
                           static_cast<int>(std::floor(gb.y()))};
  for (const grid::CellIndex cell : grid::GridLine(from, to)) {
    if (map.Contains(cell.x, cell.y) && map.StateAt(cell.x, cell.y) == grid::CellState::kOccupied) {
      return false;
    }
  }
  return true;
}

std::optional<double> DistanceToObstacle(const grid::OccupancyGrid& map, const Point2& origin,
                                         const Vector2& direction, double max_range) {
  const double step = 0.5 * map.resolution();
  for (double d = step; d <= max_range; d += step) {
    if (StateAtPoint(map, origin + d * direction) == grid::CellState::kOccupied) return d;
  }
  return std::nullopt;
}

std::optional<int> InferDominantSide(const grid::OccupancyGrid& map,
                                     const scene::PersonTrack& track, double search) {
  double left_sum = 0, right_sum = 0;
  int left_n = 0, right_n = 0;
  for (size_t i = 0; i < track.points.size(); ++i) {
    // The walking direction, or the torso heading when the person stands still.
    Vector2 forward(std::cos(track.points[i].heading), std::sin(track.points[i].heading));
    const size_t j = i + 1 < track.points.size() ? i + 1 : i - 1;
    const Vector2 step =
        (track.points[std::max(i, j)].position - track.points[std::min(i, j)].position);
    if (step.norm() > 0.02) forward = step.normalized();
    const Vector2 left(-forward.y(), forward.x());
    const Point2& p = track.points[i].position;
    if (const auto d = DistanceToObstacle(map, p, left, search)) left_sum += *d, ++left_n;
    if (const auto d = DistanceToObstacle(map, p, -left, search)) right_sum += *d, ++right_n;
  }
  // A side with no obstacle within reach counts as `search` away.
  const int n = static_cast<int>(track.points.size());
  if (left_n == 0 && right_n == 0) return std::nullopt;
  const double left_mean = (left_sum + (n - left_n) * search) / n;
  const double right_mean = (right_sum + (n - right_n) * search) / n;
  return left_mean < right_mean ? -1 : +1;
}

std::optional<Vector2> InferOpeningDirection(const grid::OccupancyGrid& map,
                                             const scene::DoorEntity& door) {
  const double width = door.width();
  if (!(width > 0.0)) return std::nullopt;
  const Vector2 along = (door.latch - door.hinge) / width;
  const Vector2 normal(-along.y(), along.x());
  const double step = 0.5 * map.resolution();
  int free_plus = 0, free_minus = 0;
  for (double s = 0.0; s <= width; s += step) {
    for (double t = 0.15; t <= std::max(0.5, width); t += step) {
      const Point2 base = door.hinge + s * along;
      free_plus += StateAtPoint(map, base + t * normal) == grid::CellState::kFree;
      free_minus += StateAtPoint(map, base - t * normal) == grid::CellState::kFree;
    }
  }
  if (free_plus == free_minus) return std::nullopt;
  return free_plus < free_minus ? normal : Vector2(-normal);
}

}  // namespace fleetmap::extrapolation
