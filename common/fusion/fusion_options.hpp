#pragma once

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::fusion {

struct FusionOptions {
  double tile_size = 10.0;   // metres: the fleet tiling every robot publishes in
  double resolution = 0.05;  // metres per fused cell; adjusted so a tile holds whole cells
  // Cells of context taken from the neighbouring fused tiles when a tile is vectorized, so that
  // walls crossing a border end at the same point in both tiles.
  int margin_cells = 4;
  vector_map::VectorizerOptions vectorizer;
  // Tiles further than this from the fleet origin are refused: UTM northings stay below 1e7 m,
  // and beyond 2e7 m no place on Earth is meant.
  double max_coordinate = 2e7;
  // Cells of the one grid FusedGrid() builds for rt/fleetmap/map (a nav_msgs/OccupancyGrid must
  // be dense). When the fused tiles span more, it shows the largest group of nearby tiles.
  int64_t max_grid_cells = int64_t{1} << 26;  // 64 M cells: 8192 x 8192, 410 m square at 5 cm

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
  // Whether `tile` lies within max_coordinate of the origin; the error names it otherwise.
  Status CheckTileInRange(const TileId& tile) const;
  // Cells along one side of a tile, and the exact resolution that fits them.
  int CellsPerTile() const;
  double FusedResolution() const;
};

}  // namespace fleetmap::fusion
