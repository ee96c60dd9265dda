#pragma once

// A polyline in cell coordinates (CellFrame) while the vectorizer builds it, and the two small
// operations every vectorization method needs on it.

#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::vector_map {

struct CellPolyline {
  std::vector<Point2> points;
  bool closed = false;
  bool start_on_border = false;  // ends at a tile-border node: never merged there
  bool end_on_border = false;
};

// The vertices points[piece[0]], points[piece[1]], ... as a polyline; a piece whose ends coincide
// becomes a closed ring (or a point).
CellPolyline MakePolyline(const std::vector<Point2>& points, const std::vector<int>& piece);

// Whether a polyline through from -> at -> to turns back on itself (by more than 120 degrees): at
// the end of a wall drawn by its two faces. The faces want different half widths, so a hairpin
// is where one polyline becomes two.
bool IsHairpin(const Point2& from, const Point2& at, const Point2& to);

// The polylines cut at their hairpin vertices (each piece keeps the vertex at its end).
std::vector<CellPolyline> SplitAtHairpins(const std::vector<CellPolyline>& polylines);

// Joins open polylines that end at the same (non-border) point, two by two, so that a vertex
// shared at a junction or a corner is stored once per pair rather than once per polyline; never
// into a hairpin. Deterministic (pairs ends in the order of the input).
std::vector<CellPolyline> MergeAtSharedEnds(std::vector<CellPolyline> polylines);

}  // namespace fleetmap::vector_map
