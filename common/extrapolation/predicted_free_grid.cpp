#include "common/extrapolation/predicted_free_grid.hpp"

#include <algorithm>
#include <cmath>

namespace fleetmap::extrapolation {

grid::OccupancyGrid SubmapGridInMapFrame(const scene::Submap& submap) {
  const grid::OccupancyGrid& g = submap.navigable;
  grid::OccupancyGrid out(
      g.width(), g.height(), g.resolution(),
      Pose2::FromTransform(submap.map_from_submap.ToTransform() * g.origin().ToTransform()));
  out.mutable_data() = g.data();
  return out;
}

FloorGrids ComposeFloorGrids(const grid::OccupancyGrid& local_map,
                             const ExtrapolationResult& result) {
  const double r = local_map.resolution();
  const Transform2 grid_from_map = local_map.origin().ToTransform().inverse();
  int x0 = 0, y0 = 0, x1 = local_map.width(), y1 = local_map.height();
  std::vector<grid::OccupancyGrid> doors;
  for (const scene::Submap& s : result.graph.submaps) {
    if (s.kind != scene::SubmapKind::kPredictedDoor) continue;
    doors.push_back(SubmapGridInMapFrame(s));
    const Point2 corner = grid_from_map * doors.back().CellCenter(0, 0) / r;
    const int cx = static_cast<int>(std::floor(corner.x()));
    const int cy = static_cast<int>(std::floor(corner.y()));
    x0 = std::min(x0, cx);
    y0 = std::min(y0, cy);
    x1 = std::max(x1, cx + doors.back().width());
    y1 = std::max(y1, cy + doors.back().height());
  }
  Transform2 map_from_out = local_map.origin().ToTransform();
  map_from_out.translate(Vector2(x0 * r, y0 * r));
  FloorGrids grids;
  grids.predicted_free =
      grid::OccupancyGrid(x1 - x0, y1 - y0, r, Pose2::FromTransform(map_from_out));
  grids.extrapolated = grids.predicted_free;
  for (int y = 0; y < local_map.height(); ++y) {
    for (int x = 0; x < local_map.width(); ++x) {
      grids.extrapolated.at(x - x0, y - y0) = local_map.at(x, y);
      if (local_map.StateAt(x, y) == grid::CellState::kFree) ++grids.observed_free_cells;
    }
  }
  auto claim = [&](int ox, int oy) {
    if (!grids.predicted_free.Contains(ox, oy)) return;
    if (grids.extrapolated.StateAt(ox, oy) != grid::CellState::kUnknown) return;
    if (grids.predicted_free.at(ox, oy) == grid::kFreeValue) return;
    grids.predicted_free.at(ox, oy) = grid::kFreeValue;
    ++grids.predicted_free_cells;
  };
  for (const grid::OccupancyGrid& door : doors) {
    for (int y = 0; y < door.height(); ++y) {
      for (int x = 0; x < door.width(); ++x) {
        if (door.StateAt(x, y) != grid::CellState::kFree) continue;
        const Point2 g = grid_from_map * door.CellCenter(x, y) / r;
        claim(static_cast<int>(std::floor(g.x())) - x0, static_cast<int>(std::floor(g.y())) - y0);
      }
    }
  }
  const grid::OccupancyGrid& people = result.conditionally_free;
  for (int y = 0; y < people.height() && y < local_map.height(); ++y) {
    for (int x = 0; x < people.width() && x < local_map.width(); ++x) {
      if (people.StateAt(x, y) == grid::CellState::kFree) claim(x - x0, y - y0);
    }
  }
  for (int y = 0; y < grids.predicted_free.height(); ++y) {
    for (int x = 0; x < grids.predicted_free.width(); ++x) {
      if (grids.predicted_free.at(x, y) == grid::kFreeValue) {
        grids.extrapolated.at(x, y) = grid::kFreeValue;
      }
    }
  }
  return grids;
}

}  // namespace fleetmap::extrapolation
