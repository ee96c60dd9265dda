#pragma once

// A robot's grid seen as the fleet's tiles, for the patch wires: which tiles of a new version of
// the grid changed, and the map_msgs/OccupancyGridUpdate that carries one tile's cells. The
// tiles are the 10 m fleet tiles the vector wire uses; a patch is the tile's cell rectangle in
// the robot's own map grid (grid::TileCellRects), so it needs an axis-aligned fleet_from_map.

#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/map_message.hpp"

namespace fleetmap::agent {

struct TileCells {
  TileId tile;
  grid::CellRect rect;  // in the robot's grid
};

// Same size, resolution and origin: a patch of one applies to the other.
bool SameGeometry(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b);

// The tiles of `current` whose cells differ from those of `previous`, which must have the same
// geometry (a broken invariant otherwise). Errors as grid::TileCellRects.
StatusOr<std::vector<TileCells>> ChangedTiles(const grid::OccupancyGrid& previous,
                                              const grid::OccupancyGrid& current,
                                              const Transform2& fleet_from_map, double tile_size);

// The tiles of `grid` with at least one known cell: what a receiver starting from an unknown map
// needs.
StatusOr<std::vector<TileCells>> KnownTiles(const grid::OccupancyGrid& grid,
                                            const Transform2& fleet_from_map, double tile_size);

// The cells of `rect` as an update of `grid`, row-major.
transport::MapUpdate PatchOf(const grid::OccupancyGrid& grid, const grid::CellRect& rect);

}  // namespace fleetmap::agent
