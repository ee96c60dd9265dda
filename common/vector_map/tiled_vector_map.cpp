#include "common/vector_map/tiled_vector_map.hpp"

#include <algorithm>
#include <cmath>

#include "common/grid/tiling.hpp"

namespace fleetmap::vector_map {
namespace {

bool AllUnknown(const grid::OccupancyGrid& grid, const CellRect& rect) {
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    const int8_t* row = grid.data().data() + static_cast<size_t>(y) * grid.width();
    if (!std::all_of(row + rect.x0, row + rect.x0 + rect.width,
                     [](int8_t value) { return value == grid::kUnknownValue; })) {
      return false;
    }
  }
  return true;
}

void Translate(const Point2& offset, std::vector<Point2>* points) {
  for (Point2& point : *points) point += offset;
}

// The tile lattice of `grid` in the fleet frame.
VertexLattice FleetLattice(const grid::OccupancyGrid& grid, const Transform2& fleet_from_map) {
  const double quantum = TileQuantum(grid.resolution());
  return {quantum, TileLatticeOrigin(fleet_from_map * grid.origin().translation(), quantum)};
}

// The per-tile vectorizer, its lattice (the fleet lattice) seen from the map frame.
Vectorizer TileVectorizer(const VertexLattice& fleet_lattice, const Transform2& fleet_from_map,
                          const TiledVectorizeOptions& options) {
  VectorizerOptions vectorizer = options.vectorizer;
  vectorizer.quantum = fleet_lattice.quantum;
  vectorizer.lattice_origin = fleet_lattice.origin - fleet_from_map.translation();
  vectorizer.frame_id = "fleet";
  return Vectorizer(vectorizer);
}

// Vectorizes one rectangle and moves the result into the fleet frame.
StatusOr<VectorMap> VectorizeRect(const Vectorizer& vectorizer, const grid::OccupancyGrid& grid,
                                  const Transform2& fleet_from_map, const CellRect& rect) {
  FLEETMAP_ASSIGN_OR_RETURN(VectorMap tile, vectorizer.VectorizeTile(grid, rect));
  const Point2 offset = fleet_from_map.translation();
  for (Polyline& polyline : tile.obstacles) Translate(offset, &polyline.points);
  for (FreePolygon& polygon : tile.free_space) {
    Translate(offset, &polygon.outer);
    for (auto& hole : polygon.holes) Translate(offset, &hole);
  }
  tile.lattice.origin += offset;
  tile.frame_id = "fleet";
  return tile;
}

}  // namespace

Point2 TileLatticeOrigin(const Point2& grid_corner, double quantum) {
  const auto offset = [quantum](double coordinate) {
    const double in_range = coordinate - std::floor(coordinate / quantum) * quantum;
    return in_range >= quantum ? 0.0 : in_range;
  };
  return {offset(grid_corner.x()), offset(grid_corner.y())};
}

size_t TiledVectorMap::ObstacleVertexCount() const {
  size_t count = 0;
  for (const auto& [id, tile] : tiles) count += tile.ObstacleVertexCount();
  return count;
}

size_t TiledVectorMap::ObstacleSegmentCount() const {
  size_t count = 0;
  for (const auto& [id, tile] : tiles) count += tile.ObstacleSegmentCount();
  return count;
}

size_t TiledVectorMap::FreeVertexCount() const {
  size_t count = 0;
  for (const auto& [id, tile] : tiles) count += tile.FreeVertexCount();
  return count;
}

VectorMap TiledVectorMap::Merged() const {
  VectorMap merged;
  merged.frame_id = frame_id;
  merged.resolution = resolution;
  merged.epsilon = epsilon;
  merged.lattice = lattice;
  for (const auto& [id, tile] : tiles) merged.Append(tile);
  return merged;
}

StatusOr<TiledVectorMap> VectorizeTiled(const grid::OccupancyGrid& grid,
                                        const Transform2& fleet_from_map,
                                        const TiledVectorizeOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            grid::TileCellRects(grid, fleet_from_map, options.tile_size));
  TiledVectorMap map;
  map.lattice = FleetLattice(grid, fleet_from_map);
  const Vectorizer vectorizer = TileVectorizer(map.lattice, fleet_from_map, options);
  map.tile_size = options.tile_size;
  map.resolution = grid.resolution();
  map.epsilon = vectorizer.EpsilonFor(grid.resolution());
  for (const auto& [id, rect] : rects) {
    if (AllUnknown(grid, rect)) continue;
    FLEETMAP_ASSIGN_OR_RETURN(VectorMap tile,
                              VectorizeRect(vectorizer, grid, fleet_from_map, rect));
    map.tiles.emplace(id, std::move(tile));
  }
  return map;
}

Status RevectorizeTile(const grid::OccupancyGrid& grid, const Transform2& fleet_from_map,
                       const TileId& tile, const TiledVectorizeOptions& options,
                       TiledVectorMap* map) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            grid::TileCellRects(grid, fleet_from_map, options.tile_size));
  const auto rect = rects.find(tile);
  if (rect == rects.end()) {
    return InvalidArgumentError("the grid has no cells in tile (" + std::to_string(tile.x) + ", " +
                                std::to_string(tile.y) + ")");
  }
  if (AllUnknown(grid, rect->second)) {
    map->tiles.erase(tile);
    return Status::Ok();
  }
  // A grid whose corner moved off the old lattice gets a new one. Each tile keeps the lattice it
  // was made on (VectorMap::lattice), so every tile still decodes right; seams are exact between
  // tiles of one lattice.
  map->lattice = FleetLattice(grid, fleet_from_map);
  FLEETMAP_ASSIGN_OR_RETURN(VectorMap vectorized,
                            VectorizeRect(TileVectorizer(map->lattice, fleet_from_map, options),
                                          grid, fleet_from_map, rect->second));
  map->tiles[tile] = std::move(vectorized);
  return Status::Ok();
}

}  // namespace fleetmap::vector_map
