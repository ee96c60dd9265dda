#pragma once

// The last stage of kDefault and its safety net (docs/vector-maps.md, kDefault step 6): every P
// point of the rectangle still farther than epsilon from every emitted segment is covered here.
// Isolated specks and small blobs land here on purpose (the skeleton drops one-pixel chains):
// uncovered points are chained through neighbours up to 2 epsilon apart (a segment between two P
// points at most 2 epsilon apart always satisfies continuity: each of its points is within epsilon
// of an end), nearest first, so specks in a row share segments, and each chain is simplified with
// the full check. A speck within epsilon of a wall's segment costs nothing.

#include <vector>

#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// Appends polylines so that every CellRaster::kOwned point is within `epsilon` (cells) of a
// segment of `polylines`. Uses CellRaster::kCovered.
void CoverRemaining(CellRaster& raster, double epsilon, std::vector<CellPolyline>& polylines);

// Appends polylines so that each of `points` (raster indices of P points, in the order chains
// start from) is within `epsilon` (cells) of a segment, as the cover stage would with only these
// points open. Uses CellRaster::kVisited (clear on entry and on return).
void CoverPoints(CellRaster& raster, double epsilon, const std::vector<int>& points,
                 std::vector<CellPolyline>& polylines);

// Sets CellRaster::kCovered on the owned P points within `epsilon` of segment [a, b], or of a
// polyline's segments.
void MarkCovered(CellRaster& raster, const Point2& a, const Point2& b, double epsilon);
void MarkCovered(CellRaster& raster, const CellPolyline& polyline, double epsilon);

}  // namespace fleetmap::vector_map
