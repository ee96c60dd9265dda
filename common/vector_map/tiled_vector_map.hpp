#pragma once

// A vector map cut into the fleet frame's square tiles: what agents publish tile by tile on
// rt/fleetmap/robot_tiles and what a .vmap file holds. Tile geometry is in the fleet frame, and
// every vertex lies on the tile lattice (multiples of TileQuantum(tile_size) from the fleet
// origin), so it survives the int16 wire encoding exactly and a vertex on a border shared by two
// tiles is the same point in both.

#include <map>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::vector_map {

// Coordinates on the wire are int16 multiples of the quantum tile_size / kTileQuantaPerSide:
// 0.625 mm for 10 m tiles. 16000 rather than a power of two so that, with 10 m tiles, the quantum
// divides half a cell of every common resolution (1, 2, 2.5, 3, 4, 5 and 10 cm): the vectorizer's
// vertices, cell centres and half-cell points, then lie on the lattice exactly and it can build
// with the full epsilon (vectorizer.hpp, VectorizerOptions::quantum). A point is decoded as
// (tile_x * kTileQuantaPerSide + local_x) * quantum, so a vertex on a border shared by two tiles
// decodes to the same point from either tile.
inline constexpr int kTileQuantaPerSide = 16000;
inline double TileQuantum(double tile_size) { return tile_size / kTileQuantaPerSide; }

struct TiledVectorMap {
  std::string frame_id = "fleet";
  double tile_size = 10.0;   // metres
  double resolution = 0.05;  // of the source grid, metres per cell
  double epsilon = 0.0;      // metres
  std::map<TileId, VectorMap> tiles;

  size_t ObstacleVertexCount() const;
  size_t ObstacleSegmentCount() const;
  size_t FreeVertexCount() const;
  // Every tile's geometry in one map (fleet frame).
  VectorMap Merged() const;
};

struct TiledVectorizeOptions {
  double tile_size = 10.0;  // metres, finite and > 0
  // The per-tile vectorizer; its quantum and lattice_origin are set by VectorizeTiled.
  VectorizerOptions vectorizer;
};

// Vectorizes a map-frame grid tile by tile. `fleet_from_map` must be a pure translation and the
// grid's origin yaw 0 (as for grid tiling). Tiles whose cells are all unknown are left out.
StatusOr<TiledVectorMap> VectorizeTiled(const grid::OccupancyGrid& grid,
                                        const Transform2& fleet_from_map,
                                        const TiledVectorizeOptions& options = {});

// Re-vectorizes the one tile `tile` of `grid` (after its cells changed) into `map`, touching no
// other tile. An all-unknown tile is removed.
Status RevectorizeTile(const grid::OccupancyGrid& grid, const Transform2& fleet_from_map,
                       const TileId& tile, const TiledVectorizeOptions& options,
                       TiledVectorMap* map);

}  // namespace fleetmap::vector_map
