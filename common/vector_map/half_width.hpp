#pragma once

// Polyline::half_width: how thick the obstacle a polyline stands for is, measured so that the
// Rasterizer gives it back. Each cell within epsilon of some polyline belongs to the nearest one.
// For each polyline, its cells beyond `min_half_width` (which the rasterizer fills anyway) are
// taken in order of distance, and the half width is the radius that maximises (occupied cells
// within it) - (other cells within it): a wall three cells thick drawn as its centre line gets one
// cell, a thin wall 0, and a single noisy cell beside a wall does not fatten the whole wall.
// Occupied cells farther than the half width (a lone bump) are the price of not over-filling.

#include <vector>

#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// In cells, one per polyline, each in [0, epsilon]. Polylines in cell coordinates.
std::vector<double> CoveredHalfWidths(const CellRaster& raster,
                                      const std::vector<CellPolyline>& polylines, double epsilon,
                                      double min_half_width);

// How well the Rasterizer paints the rectangle's cells back from `polylines` alone, with the half
// widths CoveredHalfWidths gives them (at least `min_half_width`): occupied cells painted minus
// other cells painted. Lets a stage choose between two drawings of the same obstacle.
int PaintMatch(CellRaster& raster, const std::vector<CellPolyline>& polylines, double epsilon,
               double min_half_width);

}  // namespace fleetmap::vector_map
