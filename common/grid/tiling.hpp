#pragma once

// Cutting an occupancy grid into the fleet frame's square tiles, and putting tiles back together.
// A tile (tx, ty) covers [tx, tx + 1) * tile_size by [ty, ty + 1) * tile_size in the fleet frame
// (common/core/ids.hpp); a cell belongs to the tile that contains its centre. Split followed by
// stitch gives back the original grid exactly: cells are assigned once per column and row, and
// stitching places a tile by its integer cell offset, never by re-deciding membership.

#include <map>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::grid {

struct TilingOptions {
  double tile_size = 10.0;  // metres, finite and > 0
  // Leave out tiles whose every cell is kUnknownValue: stitching into an unknown-filled grid
  // restores them.
  bool skip_unknown_tiles = true;
};

// Tile grids keyed by tile index. Each tile grid has the source's resolution, yaw 0, and its origin
// at the fleet-frame corner of its first cell. Edge tiles are partial: a tile holds only the
// source's cells, so tiles of a grid not aligned with the tile lattice have uneven sizes.
using TileGrids = std::map<TileId, OccupancyGrid>;

// The cells of `grid` that fall in each tile of the fleet frame, as rectangles of the grid (the
// same assignment SplitIntoTiles makes). Every tile the grid touches is listed, unknown or not.
// Errors as SplitIntoTiles.
StatusOr<std::map<TileId, CellRect>> TileCellRects(const OccupancyGrid& grid,
                                                   const Transform2& fleet_from_map,
                                                   double tile_size);

// Splits `grid` (in the map frame) into tiles of the fleet frame. The grid must be axis-aligned in
// the fleet frame: `fleet_from_map` a pure translation and the grid's origin yaw 0 (both within
// 1e-9 rad); anything else is kInvalidArgument, as are a bad tile size and tile indices beyond
// int32.
StatusOr<TileGrids> SplitIntoTiles(const OccupancyGrid& grid, const Transform2& fleet_from_map,
                                   const TilingOptions& options = {});

// Writes the tiles' cells into `target` (a map-frame grid, typically the geometry of the grid that
// was split, filled with kUnknownValue); cells no tile covers are left as they are. Every tile must
// match the target's resolution, lie on its cell lattice and inside it (kInvalidArgument naming the
// tile otherwise); `target` is unchanged on error.
Status StitchTiles(const TileGrids& tiles, const Transform2& fleet_from_map, OccupancyGrid* target);

// Stitches tiles into the smallest fleet-frame grid (yaw 0) that holds them all; uncovered cells
// are unknown. All tiles must share one resolution and cell lattice. No tiles gives an empty grid.
StatusOr<OccupancyGrid> StitchTiles(const TileGrids& tiles);

}  // namespace fleetmap::grid
