#pragma once

// kDefault for one rectangle of cells (docs/vector-maps.md): skeleton (skeleton.hpp), chains merged
// through junctions (chain_tracer.hpp), tile-border nodes (border_nodes.hpp), attachment of every
// P point to its nearest skeleton pixel, simplification of each chain with the full check
// (chain_simplifier.hpp: epsilon-error for the attached points, exact continuity against P), joins
// of polylines with shared ends (cell_polyline.hpp), and the cover stage (speck_cover.hpp). Both
// constraints hold for every emitted segment against every P point of the rectangle.

#include <vector>

#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// Cells of margin a CellRaster needs around the rectangle for kDefault at `epsilon` (cells).
int DefaultMargin(double epsilon);

// `raster` built with at least DefaultMargin(epsilon); `epsilon` in cells. Polylines in cells.
std::vector<CellPolyline> DefaultVectorize(CellRaster& raster, const grid::OccupancyGrid& grid,
                                           const grid::StateThresholds& thresholds, double epsilon);

}  // namespace fleetmap::vector_map
