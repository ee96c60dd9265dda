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

// The tile lattice. Vertices travel as whole steps of a quantum of half a cell, counted from a
// lattice origin in [0, quantum) per axis of the fleet frame that puts the grid's cell corners on
// the lattice. Then every cell centre and half-cell point (all the vectorizer's own vertices) is a
// lattice point and the vectorizer builds with the full epsilon (vectorizer.hpp,
// VectorizerOptions::quantum); line refits and line-end extensions are snapped to it and checked
// after snapping. The tile codec stores the quantum and the origin, and a vertex on a border shared
// by two tiles is the same number of steps from either tile.
inline double TileQuantum(double resolution) { return resolution / 2.0; }
// The origin, in [0, quantum) per axis, of the lattice that holds `grid_corner` (a fleet-frame
// point, e.g. the corner of a grid's first cell).
Point2 TileLatticeOrigin(const Point2& grid_corner, double quantum);

struct TiledVectorMap {
  std::string frame_id = "fleet";
  double tile_size = 10.0;   // metres
  double resolution = 0.05;  // of the source grid, metres per cell
  double epsilon = 0.0;      // metres
  VertexLattice lattice;     // of every tile (fleet frame)
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
