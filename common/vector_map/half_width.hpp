#pragma once

// Polyline::half_width: for each polyline, the largest distance to it of the occupied cells of the
// rectangle that it stands for. A cell stands for the polyline nearest to it among those within
// epsilon (deeper cells of a thick blob, farther than epsilon from every polyline, are outlined,
// not filled). So a wall three cells thick drawn as its centre line gets about one cell, a thin
// wall 0, and the rasterizer can give each wall back its thickness.

#include <vector>

#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// In cells, one per polyline, each in [0, epsilon]. Polylines in cell coordinates.
std::vector<double> CoveredHalfWidths(const CellRaster& raster,
                                      const std::vector<CellPolyline>& polylines, double epsilon);

}  // namespace fleetmap::vector_map
