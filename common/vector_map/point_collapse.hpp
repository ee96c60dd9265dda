#pragma once

// A short polyline whose P points all lie within epsilon of one point becomes that point: a point
// obstacle costs one vertex on the wire instead of two or more (docs/vector-maps.md, kDefault step
// 7). Thinning leaves such short pieces on blobs of two to a few cells (a speck stretched by SLAM
// blur, a chair leg); on a simulated 80 m office, two-vertex polylines shorter than two cells
// were 15 % of the polylines.

#include <vector>

#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// Replaces each open polyline no longer than 2 * `epsilon` (cells) that does not end on a tile
// border by one of its ends or its midpoint (on half cells), when every owned P point within
// epsilon of the polyline is within epsilon of that point, and the point is within epsilon of a P
// point (continuity), and when the Rasterizer paints the cells back from the point at least as
// well as from the polyline (PaintMatch: a row of three cells stays a line, as a disc would paint
// the cells beside its middle). Candidates: the centroid of those P points, the ends and the
// midpoint, each on half cells. Both constraints hold afterwards if they held before.
void CollapseToPoints(CellRaster& raster, double epsilon, std::vector<CellPolyline>& polylines);

}  // namespace fleetmap::vector_map
