#pragma once

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

  Status Validate() const;
  // Cells along one side of a tile, and the exact resolution that fits them.
  int CellsPerTile() const;
  double FusedResolution() const;
};

}  // namespace fleetmap::fusion
