#include "common/extrapolation/prediction_check.hpp"

namespace fleetmap::extrapolation {
namespace {

void Finish(PredictionCheck* check) {
  const int64_t observed = check->true_free + check->false_free;
  const int64_t total = observed + check->unobserved;
  check->precision = observed > 0 ? static_cast<double>(check->true_free) / observed : 0.0;
  check->observed_fraction = total > 0 ? static_cast<double>(observed) / total : 0.0;
}

// Adds the cell whose map-frame centre is `map_point` to `check`.
void Score(const Point2& map_point, const grid::OccupancyGrid& observed, PredictionCheck* check) {
  const std::optional<grid::CellIndex> cell = observed.CellAt(map_point);
  if (!cell) {
    ++check->unobserved;
    return;
  }
  switch (observed.StateAt(cell->x, cell->y)) {
    case grid::CellState::kFree:
      ++check->true_free;
      break;
    case grid::CellState::kOccupied:
      ++check->false_free;
      break;
    case grid::CellState::kUnknown:
      ++check->unobserved;
      break;
  }
}

bool Known(const Point2& map_point, const grid::OccupancyGrid& grid) {
  const std::optional<grid::CellIndex> cell = grid.CellAt(map_point);
  return cell && grid.StateAt(cell->x, cell->y) != grid::CellState::kUnknown;
}

}  // namespace

PredictionCheck& PredictionCheck::operator+=(const PredictionCheck& other) {
  true_free += other.true_free;
  false_free += other.false_free;
  unobserved += other.unobserved;
  Finish(this);
  return *this;
}

PredictionCheck CheckPrediction(const scene::Submap& predicted,
                                const grid::OccupancyGrid& observed) {
  PredictionCheck check;
  const Transform2 map_from_submap = predicted.map_from_submap.ToTransform();
  const grid::OccupancyGrid& grid = predicted.navigable;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.StateAt(x, y) != grid::CellState::kFree) continue;
      Score(map_from_submap * grid.CellCenter(x, y), observed, &check);
    }
  }
  Finish(&check);
  return check;
}

PredictionCheck CheckPredictedGrid(const grid::OccupancyGrid& predicted,
                                   const grid::OccupancyGrid& observed,
                                   const grid::OccupancyGrid* already_known) {
  PredictionCheck check;
  for (int y = 0; y < predicted.height(); ++y) {
    for (int x = 0; x < predicted.width(); ++x) {
      if (predicted.StateAt(x, y) != grid::CellState::kFree) continue;
      const Point2 map_point = predicted.CellCenter(x, y);
      if (already_known != nullptr && Known(map_point, *already_known)) continue;
      Score(map_point, observed, &check);
    }
  }
  Finish(&check);
  return check;
}

}  // namespace fleetmap::extrapolation
