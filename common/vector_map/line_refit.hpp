#pragma once

// Moves the vertices of kDefault's polylines off the skeleton's cell centres where the band the
// Rasterizer paints around them (radius max(half width, min radius)) then matches the cells better.
// Thinning puts every vertex on a cell centre, so a wall an even number of cells thick (two is the
// commonest in SLAM grids) or a wall a fraction of a cell off the lattice comes back one row too
// thin or too thick, whatever its half width: the band is symmetric about a line through cell
// centres.
//
// The fit: each segment stands for the occupied cells within epsilon whose nearest segment it is.
// A total-least-squares line is fitted through their centres (through the fixed end, if one end
// may not move; the segment's own direction is kept where the cells do not define one). A vertex
// between two segments moves to the intersection of their fitted lines (to the mean of its
// projections onto them where they are nearly parallel); a free end moves onto its line and out to
// the farthest of its cells. The polyline's half width is then refitted for the moved geometry:
// the radius that maximises the match below.
//
// Contract, on the final (snapped) geometry and against the full epsilon: every changed segment is
// continuous (the exact test against P), and every P point of the rectangle stays within epsilon
// of some segment (coverage counts over exact distances); vertices whose move breaks either keep
// their old place. A polyline's move is kept only if it raises the match of its band to the cells:
// (occupied cells of the rectangle it paints) + (cells not occupied, anywhere, it leaves
// unpainted), counted over the cells no other polyline paints, with the radius a reader will see
// (`emitted_half_width`). So no constraint breaks and the match never falls. Tile-border nodes
// (which the neighbouring tile shares), vertices shared by two polylines (junctions) and point
// obstacles never move, and no vertex is added or removed.
//
// Thread-safety: one call per thread at a time (per-thread scratch images).

#include <functional>
#include <vector>

#include "common/core/types.hpp"
#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

struct LineRefitOptions {
  double epsilon = 0.0;     // cells; the full epsilon the output must meet
  double min_radius = 0.5;  // cells; the rasterizer's minimum half width
  // Cell coordinates -> the point a reader will see (lattice snapping); identity if empty.
  std::function<Point2(const Point2&)> snap;
  // A half width in cells -> the half width in cells a reader will see (as emitted: capped at
  // epsilon, rounded up to whole quanta); identity if empty.
  std::function<double(double)> emitted_half_width;
  // Cells: a polyline whose fit moves none of its vertices this far is left alone.
  double min_move = 0.05;
  // Cells: no vertex moves farther (a fit that asks for more is not trusted).
  double max_move = 1.0;
  // Cells; > 0 puts moved vertices on multiples of it (cell centres are integers) before
  // snapping. Half a cell is what a wall an even number of cells thick needs, and keeps the
  // coordinates regular enough to compress (docs/vector-maps.md, "Line refit").
  double position_step = 0.5;
};

struct LineRefitStats {
  int polylines_moved = 0;  // polylines whose new geometry was kept
  int vertices_moved = 0;
};

// `half_widths[k]` is polyline k's half width in cells (CoveredHalfWidths); it is replaced for
// every polyline that moves. Polylines in cell coordinates, already snapped.
LineRefitStats RefitLines(const CellRaster& raster, const LineRefitOptions& options,
                          std::vector<CellPolyline>& polylines, std::vector<double>& half_widths);

}  // namespace fleetmap::vector_map
