#include "common/grid/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace fleetmap::grid {
namespace {

constexpr double kMaxYaw = 1e-9;            // radians: what counts as "no rotation"
constexpr double kLatticeTolerance = 1e-6;  // cells: how far a tile origin may be off the lattice

// A run of consecutive columns (or rows) [begin, end) that fall in one tile column (or row).
struct Run {
  int32_t tile = 0;
  int begin = 0;
  int end = 0;
};

std::string Name(const TileId& id) {
  std::ostringstream out;
  out << id;
  return out.str();
}

double RotationAngle(const Transform2& transform) {
  const auto& linear = transform.linear();
  return std::atan2(linear(1, 0), linear(0, 0));
}

// floor(a / b) for b > 0.
int64_t FloorDiv(int64_t a, int64_t b) { return a / b - ((a % b != 0) && (a < 0)); }

// The tile of each of `count` cells along one axis, grouped into runs. `corner` is the fleet
// coordinate of cell 0's outer edge. When the tile size is a whole number of cells and the corner
// lies on the cell lattice through 0, the index is computed in integers; otherwise from the
// floating-point centre. Either way each cell is decided once and runs are contiguous, because
// floor((corner + (i + 0.5) * res) / size) never decreases with i.
StatusOr<std::vector<Run>> AxisRuns(double corner, int count, double resolution, double tile_size,
                                    const char* axis) {
  const double cells_per_tile = tile_size / resolution;
  const double rounded_cells = std::round(cells_per_tile);
  const double corner_cells = corner / resolution;
  const double rounded_corner = std::round(corner_cells);
  const bool integral = rounded_cells >= 1.0 && rounded_cells < 1e12 &&
                        std::abs(cells_per_tile - rounded_cells) <= 1e-9 * rounded_cells &&
                        std::abs(rounded_corner) < 1e15 &&
                        std::abs(corner_cells - rounded_corner) <= kLatticeTolerance;
  std::vector<Run> runs;
  for (int i = 0; i < count; ++i) {
    double tile = 0.0;
    if (integral) {
      tile = static_cast<double>(
          FloorDiv(static_cast<int64_t>(rounded_corner) + i, static_cast<int64_t>(rounded_cells)));
    } else {
      tile = std::floor((corner + (i + 0.5) * resolution) / tile_size);
    }
    if (!(tile >= std::numeric_limits<int32_t>::min() &&
          tile <= std::numeric_limits<int32_t>::max())) {
      return InvalidArgumentError(std::string("tile index along ") + axis +
                                  " is out of the int32 range (cell " + std::to_string(i) +
                                  ", tile_size " + std::to_string(tile_size) + " m)");
    }
    const auto tile_index = static_cast<int32_t>(tile);
    if (runs.empty() || runs.back().tile != tile_index) {
      runs.push_back({tile_index, i, i + 1});
    } else {
      runs.back().end = i + 1;
    }
  }
  return runs;
}

Status CheckAxisAligned(const Transform2& fleet_from_map, double origin_yaw) {
  const Eigen::Vector2d translation = fleet_from_map.translation();
  if (!fleet_from_map.matrix().allFinite()) {
    return InvalidArgumentError("fleet_from_map is not finite");
  }
  const double rotation = RotationAngle(fleet_from_map);
  if (std::abs(rotation) > kMaxYaw) {
    return InvalidArgumentError("fleet_from_map rotates by " + std::to_string(rotation) +
                                " rad; tiling needs a pure translation (rotated maps are not "
                                "supported)");
  }
  if (!(std::abs(origin_yaw) <= kMaxYaw)) {
    return InvalidArgumentError("the grid's origin yaw is " + std::to_string(origin_yaw) +
                                " rad; tiling needs a grid axis-aligned with the fleet frame");
  }
  if (!translation.allFinite()) return InvalidArgumentError("fleet_from_map is not finite");
  return Status::Ok();
}

// The whole-cell offset of `value` from `reference` along one axis, if it is on the lattice.
std::optional<int64_t> LatticeOffset(double value, double reference, double resolution) {
  const double cells = (value - reference) / resolution;
  const double rounded = std::round(cells);
  if (!std::isfinite(cells) || std::abs(cells - rounded) > kLatticeTolerance ||
      std::abs(rounded) > 1e15) {
    return std::nullopt;
  }
  return static_cast<int64_t>(rounded);
}

void CopyTile(const OccupancyGrid& tile, int64_t x0, int64_t y0, OccupancyGrid* target) {
  if (tile.empty()) return;
  for (int y = 0; y < tile.height(); ++y) {
    const int8_t* from = tile.data().data() + static_cast<size_t>(y) * tile.width();
    int8_t* to = &target->at(static_cast<int>(x0), static_cast<int>(y0) + y);
    std::memcpy(to, from, static_cast<size_t>(tile.width()));
  }
}

}  // namespace

StatusOr<std::map<TileId, CellRect>> TileCellRects(const OccupancyGrid& grid,
                                                   const Transform2& fleet_from_map,
                                                   double tile_size) {
  if (!std::isfinite(tile_size) || tile_size <= 0.0) {
    return InvalidArgumentError("tile_size must be a finite number > 0 metres, got " +
                                std::to_string(tile_size));
  }
  FLEETMAP_RETURN_IF_ERROR(CheckAxisAligned(fleet_from_map, grid.origin().yaw));
  std::map<TileId, CellRect> rects;
  if (grid.empty()) return rects;
  // The fleet frame's coordinates of cell (0, 0)'s outer corner. Stitching recomputes the same
  // expression, so both sides agree on it to the last bit.
  const double corner_x = grid.origin().x + fleet_from_map.translation().x();
  const double corner_y = grid.origin().y + fleet_from_map.translation().y();
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<Run> columns,
                            AxisRuns(corner_x, grid.width(), grid.resolution(), tile_size, "x"));
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<Run> rows,
                            AxisRuns(corner_y, grid.height(), grid.resolution(), tile_size, "y"));
  for (const Run& row : rows) {
    for (const Run& column : columns) {
      rects.emplace(
          TileId{column.tile, row.tile},
          CellRect{column.begin, row.begin, column.end - column.begin, row.end - row.begin});
    }
  }
  return rects;
}

StatusOr<TileGrids> SplitIntoTiles(const OccupancyGrid& grid, const Transform2& fleet_from_map,
                                   const TilingOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            TileCellRects(grid, fleet_from_map, options.tile_size));
  const double resolution = grid.resolution();
  const double corner_x = grid.origin().x + fleet_from_map.translation().x();
  const double corner_y = grid.origin().y + fleet_from_map.translation().y();
  TileGrids tiles;
  for (const auto& [id, rect] : rects) {
    const Pose2 origin{corner_x + rect.x0 * resolution, corner_y + rect.y0 * resolution, 0.0};
    OccupancyGrid tile(rect.width, rect.height, resolution, origin);
    bool all_unknown = true;
    for (int y = 0; y < rect.height; ++y) {
      const int8_t* from =
          grid.data().data() + static_cast<size_t>(rect.y0 + y) * grid.width() + rect.x0;
      int8_t* to = tile.mutable_data().data() + static_cast<size_t>(y) * rect.width;
      std::memcpy(to, from, static_cast<size_t>(rect.width));
      all_unknown = all_unknown &&
                    std::all_of(to, to + rect.width, [](int8_t v) { return v == kUnknownValue; });
    }
    if (all_unknown && options.skip_unknown_tiles) continue;
    tiles.emplace(id, std::move(tile));
  }
  return tiles;
}

Status StitchTiles(const TileGrids& tiles, const Transform2& fleet_from_map,
                   OccupancyGrid* target) {
  if (target == nullptr) return InvalidArgumentError("StitchTiles: no target grid");
  FLEETMAP_RETURN_IF_ERROR(CheckAxisAligned(fleet_from_map, target->origin().yaw));
  const double resolution = target->resolution();
  const double corner_x = target->origin().x + fleet_from_map.translation().x();
  const double corner_y = target->origin().y + fleet_from_map.translation().y();
  struct Placement {
    const OccupancyGrid* tile;
    int64_t x0;
    int64_t y0;
  };
  std::vector<Placement> placements;
  placements.reserve(tiles.size());
  // Check every tile before writing any cell, so a bad tile leaves the target untouched.
  for (const auto& [id, tile] : tiles) {
    if (!SameResolution(tile.resolution(), resolution)) {
      return InvalidArgumentError(Name(id) + ": resolution " + std::to_string(tile.resolution()) +
                                  " m differs from the target's " + std::to_string(resolution));
    }
    if (std::abs(tile.origin().yaw) > kMaxYaw) {
      return InvalidArgumentError(Name(id) + ": origin yaw must be 0");
    }
    const std::optional<int64_t> x0 = LatticeOffset(tile.origin().x, corner_x, resolution);
    const std::optional<int64_t> y0 = LatticeOffset(tile.origin().y, corner_y, resolution);
    if (!x0 || !y0) {
      return InvalidArgumentError(Name(id) + ": origin is not on the target grid's cell lattice");
    }
    if (*x0 < 0 || *y0 < 0 || *x0 + tile.width() > target->width() ||
        *y0 + tile.height() > target->height()) {
      return InvalidArgumentError(Name(id) + ": covers cells [" + std::to_string(*x0) + ", " +
                                  std::to_string(*x0 + tile.width()) + ") x [" +
                                  std::to_string(*y0) + ", " + std::to_string(*y0 + tile.height()) +
                                  "), outside the target's " + std::to_string(target->width()) +
                                  " x " + std::to_string(target->height()) + " cells");
    }
    placements.push_back({&tile, *x0, *y0});
  }
  for (const Placement& placement : placements) {
    CopyTile(*placement.tile, placement.x0, placement.y0, target);
  }
  return Status::Ok();
}

StatusOr<OccupancyGrid> StitchTiles(const TileGrids& tiles) {
  if (tiles.empty()) return OccupancyGrid();
  const OccupancyGrid& reference = tiles.begin()->second;
  const double resolution = reference.resolution();
  int64_t min_x = std::numeric_limits<int64_t>::max();
  int64_t min_y = std::numeric_limits<int64_t>::max();
  int64_t max_x = std::numeric_limits<int64_t>::min();
  int64_t max_y = std::numeric_limits<int64_t>::min();
  for (const auto& [id, tile] : tiles) {
    if (!SameResolution(tile.resolution(), resolution)) {
      return InvalidArgumentError(Name(id) + ": resolution " + std::to_string(tile.resolution()) +
                                  " m differs from " + Name(tiles.begin()->first) + "'s " +
                                  std::to_string(resolution));
    }
    if (std::abs(tile.origin().yaw) > kMaxYaw) {
      return InvalidArgumentError(Name(id) + ": origin yaw must be 0");
    }
    const auto x0 = LatticeOffset(tile.origin().x, reference.origin().x, resolution);
    const auto y0 = LatticeOffset(tile.origin().y, reference.origin().y, resolution);
    if (!x0 || !y0) {
      return InvalidArgumentError(Name(id) + ": origin is not on " + Name(tiles.begin()->first) +
                                  "'s cell lattice");
    }
    min_x = std::min(min_x, *x0);
    min_y = std::min(min_y, *y0);
    max_x = std::max(max_x, *x0 + tile.width());
    max_y = std::max(max_y, *y0 + tile.height());
  }
  if (max_x - min_x > std::numeric_limits<int32_t>::max() ||
      max_y - min_y > std::numeric_limits<int32_t>::max()) {
    return InvalidArgumentError("stitched tiles would span more than 2^31 cells");
  }
  // Same arithmetic as a split's tile origins, so a split's first tile lands back on its corner.
  const Pose2 origin{reference.origin().x + static_cast<double>(min_x) * resolution,
                     reference.origin().y + static_cast<double>(min_y) * resolution, 0.0};
  OccupancyGrid stitched(static_cast<int>(max_x - min_x), static_cast<int>(max_y - min_y),
                         resolution, origin);
  FLEETMAP_RETURN_IF_ERROR(StitchTiles(tiles, Transform2::Identity(), &stitched));
  return stitched;
}

}  // namespace fleetmap::grid
