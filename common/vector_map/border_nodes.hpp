#pragma once

// Tile-border nodes (docs/vector-maps.md, "Tiles and seams"): where a skeleton chain leaves the
// tile, it is extended to a point on the border line computed only from the two lines of cells on
// either side of that border, so the tiles on both sides compute the same point, bit for bit.

#include <optional>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

class BorderNodes {
 public:
  // `raster` must have CellRaster::kAnchor set (ThinToSkeleton).
  BorderNodes(const CellRaster& raster, const grid::OccupancyGrid& grid,
              const grid::StateThresholds& thresholds)
      : raster_(raster), grid_(grid), thresholds_(thresholds) {}

  // The node for a chain end pixel `index` (raster index) next to an anchor across a tile side,
  // if the chain comes from inside the tile: `next`, the chain's pixel after the end (-1 for a
  // one-pixel chain), must be one step farther from that side. A chain running along the border,
  // or a lone pixel on it (pieces of a wall lying on the border, cut by thinning), gets no node:
  // its P points are covered along the wall instead, and a node would add a segment per piece.
  std::optional<Point2> For(int index, int next) const;

 private:
  bool Occupied(int x, int y) const;
  std::optional<Point2> Node(int x, int y, int out_x, int out_y) const;

  const CellRaster& raster_;
  const grid::OccupancyGrid& grid_;
  grid::StateThresholds thresholds_;
};

}  // namespace fleetmap::vector_map
