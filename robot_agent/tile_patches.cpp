#include "robot_agent/tile_patches.hpp"

#include <algorithm>
#include <cstring>

#include "common/core/check.hpp"
#include "common/grid/tiling.hpp"

namespace fleetmap::agent {
namespace {

const int8_t* Row(const grid::OccupancyGrid& grid, int x, int y) {
  return grid.data().data() + static_cast<size_t>(y) * grid.width() + x;
}

bool RowsDiffer(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                const grid::CellRect& rect) {
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    if (std::memcmp(Row(a, rect.x0, y), Row(b, rect.x0, y), static_cast<size_t>(rect.width)) != 0) {
      return true;
    }
  }
  return false;
}

bool AnyKnown(const grid::OccupancyGrid& grid, const grid::CellRect& rect) {
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    const int8_t* row = Row(grid, rect.x0, y);
    if (std::any_of(row, row + rect.width, [](int8_t v) { return v != grid::kUnknownValue; })) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool SameGeometry(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b) {
  return a.width() == b.width() && a.height() == b.height() && a.resolution() == b.resolution() &&
         a.origin() == b.origin();
}

StatusOr<std::vector<TileCells>> ChangedTiles(const grid::OccupancyGrid& previous,
                                              const grid::OccupancyGrid& current,
                                              const Transform2& fleet_from_map, double tile_size) {
  FLEETMAP_CHECK(SameGeometry(previous, current), "ChangedTiles needs grids of one geometry");
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            grid::TileCellRects(current, fleet_from_map, tile_size));
  std::vector<TileCells> changed;
  for (const auto& [tile, rect] : rects) {
    if (RowsDiffer(previous, current, rect)) changed.push_back({tile, rect});
  }
  return changed;
}

StatusOr<std::vector<TileCells>> KnownTiles(const grid::OccupancyGrid& grid,
                                            const Transform2& fleet_from_map, double tile_size) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects, grid::TileCellRects(grid, fleet_from_map, tile_size));
  std::vector<TileCells> known;
  for (const auto& [tile, rect] : rects) {
    if (AnyKnown(grid, rect)) known.push_back({tile, rect});
  }
  return known;
}

transport::MapUpdate PatchOf(const grid::OccupancyGrid& grid, const grid::CellRect& rect) {
  transport::MapUpdate patch;
  patch.x = rect.x0;
  patch.y = rect.y0;
  patch.width = rect.width;
  patch.height = rect.height;
  patch.data.resize(static_cast<size_t>(rect.cell_count()));
  for (int row = 0; row < rect.height; ++row) {
    std::memcpy(patch.data.data() + static_cast<size_t>(row) * rect.width,
                Row(grid, rect.x0, rect.y0 + row), static_cast<size_t>(rect.width));
  }
  return patch;
}

}  // namespace fleetmap::agent
