#include "common/route_graph/route_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace fleetmap::route_graph {
namespace {

// The grid cells (clamped to the grid) whose centres may lie within the axis-aligned box of
// `corners` (map frame).
grid::CellRect CellsAround(const grid::OccupancyGrid& grid, const std::vector<Point2>& corners) {
  double x0 = corners.front().x(), x1 = x0, y0 = corners.front().y(), y1 = y0;
  for (const Point2& corner : corners) {
    x0 = std::min(x0, corner.x());
    x1 = std::max(x1, corner.x());
    y0 = std::min(y0, corner.y());
    y1 = std::max(y1, corner.y());
  }
  const double res = grid.resolution();
  const int cx0 = std::max(0, static_cast<int>(std::floor((x0 - grid.origin().x) / res)));
  const int cy0 = std::max(0, static_cast<int>(std::floor((y0 - grid.origin().y) / res)));
  const int cx1 =
      std::min(grid.width() - 1, static_cast<int>(std::floor((x1 - grid.origin().x) / res)));
  const int cy1 =
      std::min(grid.height() - 1, static_cast<int>(std::floor((y1 - grid.origin().y) / res)));
  if (cx1 < cx0 || cy1 < cy0) return {0, 0, 0, 0};
  return {cx0, cy0, cx1 - cx0 + 1, cy1 - cy0 + 1};
}

// The cells of a door, hinge to latch, that are not free: shut when a robot saw it.
void AddDoor(const grid::OccupancyGrid& grid, const std::array<Point2, 2>& door,
             const grid::StateThresholds& thresholds, std::vector<int64_t>* cells) {
  const Vector2 along = door[1] - door[0];
  const double length = along.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const Vector2 unit = along / length;
  const double depth = RouteOverlay::kDoorDepth;
  const Vector2 across(-unit.y() * depth, unit.x() * depth);
  const grid::CellRect box =
      CellsAround(grid, {door[0] + across, door[0] - across, door[1] + across, door[1] - across});
  for (int y = box.y0; y < box.y0 + box.height; ++y) {
    for (int x = box.x0; x < box.x0 + box.width; ++x) {
      const Vector2 offset = grid.CellCenter(x, y) - door[0];
      const double t = offset.dot(unit);
      if (t < 0.0 || t > length || std::abs(offset.dot(Vector2(-unit.y(), unit.x()))) > depth) {
        continue;
      }
      if (grid.StateAt(x, y, thresholds) == grid::CellState::kFree) continue;
      cells->push_back(static_cast<int64_t>(y) * grid.width() + x);
    }
  }
}

void AddPredicted(const grid::OccupancyGrid& grid, const scene::Submap& submap,
                  const grid::StateThresholds& thresholds, std::vector<int64_t>* cells) {
  const grid::OccupancyGrid& navigable = submap.navigable;
  if (navigable.empty()) return;
  const Transform2 map_from_cells =
      submap.map_from_submap.ToTransform() * navigable.origin().ToTransform();
  const double w = navigable.width() * navigable.resolution();
  const double h = navigable.height() * navigable.resolution();
  const grid::CellRect box =
      CellsAround(grid, {map_from_cells * Point2(0, 0), map_from_cells * Point2(w, 0),
                         map_from_cells * Point2(0, h), map_from_cells * Point2(w, h)});
  const Transform2 submap_from_map = submap.map_from_submap.ToTransform().inverse();
  for (int y = box.y0; y < box.y0 + box.height; ++y) {
    for (int x = box.x0; x < box.x0 + box.width; ++x) {
      if (grid.StateAt(x, y, thresholds) != grid::CellState::kUnknown) continue;
      const std::optional<grid::CellIndex> cell =
          navigable.CellAt(submap_from_map * grid.CellCenter(x, y));
      if (!cell || navigable.StateAt(cell->x, cell->y) != grid::CellState::kFree) continue;
      cells->push_back(static_cast<int64_t>(y) * grid.width() + x);
    }
  }
}

void AddObject(const grid::OccupancyGrid& grid, const MovableObject& object,
               const grid::StateThresholds& thresholds,
               std::vector<std::pair<int64_t, uint32_t>>* cells) {
  const scene::Patch& patch = object.patch;
  if (patch.empty() || patch.resolution <= 0.0) return;
  const double reach = 0.5 * std::hypot(patch.width, patch.height) * patch.resolution;
  for (const Pose2& sighting : object.sightings) {
    const Point2 centre(sighting.x, sighting.y);
    const grid::CellRect box =
        CellsAround(grid, {centre - Point2(reach, reach), centre + Point2(reach, reach)});
    const Transform2 object_from_map = sighting.ToTransform().inverse();
    for (int y = box.y0; y < box.y0 + box.height; ++y) {
      for (int x = box.x0; x < box.x0 + box.width; ++x) {
        if (grid.StateAt(x, y, thresholds) != grid::CellState::kOccupied) continue;
        // Patch cell (i, j) is centred at ((i - (width - 1) / 2) res, (j - (height - 1) / 2) res).
        const Point2 local = object_from_map * grid.CellCenter(x, y);
        const int i =
            static_cast<int>(std::lround(local.x() / patch.resolution + 0.5 * (patch.width - 1)));
        const int j =
            static_cast<int>(std::lround(local.y() / patch.resolution + 0.5 * (patch.height - 1)));
        if (i < 0 || j < 0 || i >= patch.width || j >= patch.height) continue;
        if (patch.at(i, j) < RouteOverlay::kObjectCell) continue;
        cells->push_back({static_cast<int64_t>(y) * grid.width() + x, object.id});
      }
    }
  }
}

}  // namespace

RouteOverlay RouteOverlay::Make(const grid::OccupancyGrid& grid,
                                const std::vector<PredictedSpace>& predicted,
                                const std::vector<MovableObject>& objects,
                                const grid::StateThresholds& thresholds) {
  RouteOverlay overlay;
  if (grid.empty()) return overlay;
  for (const PredictedSpace& space : predicted) {
    AddPredicted(grid, space.submap, thresholds, &overlay.predicted_);
    if (space.door) AddDoor(grid, *space.door, thresholds, &overlay.predicted_);
  }
  std::sort(overlay.predicted_.begin(), overlay.predicted_.end());
  overlay.predicted_.erase(std::unique(overlay.predicted_.begin(), overlay.predicted_.end()),
                           overlay.predicted_.end());
  for (const MovableObject& object : objects)
    AddObject(grid, object, thresholds, &overlay.objects_);
  // A cell two footprints share belongs to the object with the smaller id.
  std::sort(overlay.objects_.begin(), overlay.objects_.end());
  overlay.objects_.erase(
      std::unique(overlay.objects_.begin(), overlay.objects_.end(),
                  [](const auto& a, const auto& b) { return a.first == b.first; }),
      overlay.objects_.end());
  return overlay;
}

bool RouteOverlay::Predicted(int64_t cell) const {
  return std::binary_search(predicted_.begin(), predicted_.end(), cell);
}

std::optional<uint32_t> RouteOverlay::ObjectAt(int64_t cell) const {
  const auto it =
      std::lower_bound(objects_.begin(), objects_.end(), cell,
                       [](const auto& entry, int64_t key) { return entry.first < key; });
  if (it == objects_.end() || it->first != cell) return std::nullopt;
  return it->second;
}

void RouteOverlay::Open(grid::OccupancyGrid* grid) const {
  std::vector<int8_t>& data = grid->mutable_data();
  for (const int64_t cell : predicted_) data[static_cast<size_t>(cell)] = grid::kFreeValue;
  for (const auto& [cell, id] : objects_) data[static_cast<size_t>(cell)] = grid::kFreeValue;
}

std::vector<int64_t> RouteOverlay::Differences(const RouteOverlay& other) const {
  std::vector<int64_t> cells;
  std::set_symmetric_difference(predicted_.begin(), predicted_.end(), other.predicted_.begin(),
                                other.predicted_.end(), std::back_inserter(cells));
  std::vector<std::pair<int64_t, uint32_t>> objects;
  std::set_symmetric_difference(objects_.begin(), objects_.end(), other.objects_.begin(),
                                other.objects_.end(), std::back_inserter(objects));
  for (const auto& [cell, id] : objects) cells.push_back(cell);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

}  // namespace fleetmap::route_graph
