#pragma once

// Lengthens open polylines at their free ends so that the band the Rasterizer paints around them
// (radius max(half width, min radius)) reaches the occupied cells just beyond an end: thinning
// shortens a line end by about a cell, and a band of half a cell around the shortened end misses
// the end cell. Such a cell would otherwise be left unpainted, so the free space must hold a hole
// for it (bytes) and it comes back unknown (MS). The end vertex moves to the centre of such a cell
// ahead of it (within 2 epsilon; no vertex is added, and cell centres are the coordinates the
// other vertices use, so the bytes compress as before).
//
// Contract: the constraints are kept exactly, on the final (snapped) geometry. An extension is
// accepted only if (a) the lengthened segment is continuous at epsilon (exact test against P),
// (b) every P point within epsilon of the old segment is within epsilon of the new one, (c) every
// cell the old segment painted is still painted, and (d) it newly paints more occupied cells of
// the tile than cells that are not occupied (never an invented obstacle, never a net loss).
// Ends on a tile border (seams) and closed polylines are left alone.

#include <functional>
#include <vector>

#include "common/core/types.hpp"
#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

struct EndExtensionOptions {
  double epsilon = 0.0;     // cells; the full epsilon the output must meet
  double min_radius = 0.5;  // cells; the rasterizer's minimum half width
  double snap_slack = 0.0;  // cells; the largest move of `snap`
  // Cell coordinates -> the point a reader will see (lattice snapping); identity if empty.
  std::function<Point2(const Point2&)> snap;
};

// `radii[k]` is polyline k's half width in cells (before the minimum). Returns the number of ends
// extended. Polylines in cell coordinates, already snapped.
int ExtendLineEnds(const CellRaster& raster, const std::vector<double>& radii,
                   const EndExtensionOptions& options, std::vector<CellPolyline>& polylines);

}  // namespace fleetmap::vector_map
