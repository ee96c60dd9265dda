#pragma once

// Explored free space of a rectangle of cells as polygons with holes, in cell coordinates
// (CellFrame). Outlines pass through the centres of the region's boundary cells (OpenCV border
// following) and are simplified with Douglas-Peucker at `epsilon_cells`; the Rasterizer fills a
// polygon including its outline, which rebuilds an unsimplified region exactly.
//
// The region is not just the free cells. The Rasterizer paints obstacles over free space, so the
// cells it will paint (`painted`) are "don't care": they join the region wherever they are at least
// one cell away from a must-stay-unknown cell (unknown, or occupied but not painted). Then an
// obstacle inside free space costs no hole, a wall between free and unknown space pulls the outline
// to its far side only where that is safe, and Douglas-Peucker errors of up to epsilon land in
// don't-care cells rather than in unknown ones. Components without a free cell are dropped, and so
// are holes that simplify to fewer than 3 vertices (they enclose no cell).
//
// Occupied cells that are not painted split in two. Those within epsilon of an obstacle edge
// (`near_obstacles`: bumps of a ragged wall just beyond its half width, a corner cell a segment
// cuts across) are already stood for by the obstacles within the map's error bound, the very bound
// the epsilon-error constraint grants them; they are don't care too, so they cost no hole of their
// own. The others (the inside of a solid region, an obstacle the vector map lost) must never come
// back free: the outlines are simplified by OutlineSimplifier, which guarantees it, so such cells
// come back unknown (a solid block: its painted outline around an unknown inside, a hole of the
// free polygon).

#include <cstdint>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/delimitation.hpp"

namespace fleetmap::vector_map {

struct CellPolygon {
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> holes;
};

struct FreeSpaceOptions {
  double epsilon_cells = 1.0;
  // One byte per cell of the rectangle (row-major), non-zero where the rasterizer paints an
  // obstacle anyway (PaintedCells); such cells may fall inside or outside the polygons. Null: none
  // (then no occupied cell of the rectangle comes back free).
  const std::vector<uint8_t>* painted = nullptr;
  // Same layout, non-zero where a cell's centre lies within epsilon of an obstacle edge: occupied
  // cells there that are not painted are don't care as well. Null: every unpainted occupied cell
  // is guarded.
  const std::vector<uint8_t>* near_obstacles = nullptr;
};

std::vector<CellPolygon> ExtractFreeSpace(const grid::OccupancyGrid& grid, const CellRect& rect,
                                          const grid::StateThresholds& thresholds,
                                          const FreeSpaceOptions& options);

}  // namespace fleetmap::vector_map
