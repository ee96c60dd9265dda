#pragma once

// kPaper: the paper's greedy vectorization, kept faithful for comparison (ALGORITHMS.md 1,
// docs/vector-maps.md). Graph on P with an edge wherever two points are within epsilon, then
// shortcut removal of degree-2 vertices v2 while dist(v2, seg(v1, v3)) < epsilon (only v2 is
// checked, so it can break the epsilon-error constraint), then decomposition into polylines
// through degree-2 vertices.

#include <vector>

#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/delimitation.hpp"

namespace fleetmap::vector_map {

// P points of `rect`; `epsilon` in cells; polylines in cell coordinates.
std::vector<CellPolyline> PaperVectorize(const Delimitation& delimitation, const CellRect& rect,
                                         double epsilon);

}  // namespace fleetmap::vector_map
