#pragma once

// Pockets inside walls, for thinning (docs/vector-maps.md, kDefault step 1). A SLAM grid often
// leaves the inside of a wall it saw from both sides unknown, or lets a ray slip into it: a
// pocket of one or a few cells enclosed by the wall's occupied cells. Thinning keeps the topology
// of what it thins, so each pocket would leave a loop of skeleton around it, and a wall full of
// pockets would come out as a ladder of small rings (three or more vertices per pocket) instead
// of one centre line.
//
// A wall pocket here is a 4-connected set of non-occupied cells, enclosed by occupied cells, of at
// most kMaxWallPocketCells cells, each of which lies between two occupied cells on opposite sides
// (E-W, N-S or a diagonal): a slit one cell wide, so a centre line through it stays within a cell
// of both faces. A wider hole (a hollow pillar, a room) keeps its ring. Thinning treats pocket
// cells like occupied ones: skeleton candidates inside the rectangle, fixed anchors just outside
// it (a pocket may reach into the raster's margin, so neighbouring tiles see the same pocket).
// This only guides where the skeleton runs: the delimitation P is still that of the grid, and
// every segment is still checked against both constraints.

#include <vector>

#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// Larger slits (the unseen inside of a wall seen from both sides) keep their two face lines: one
// centre line through a wall three cells thick has only 0.41 cell of slack for ragged faces, and
// on the simulated SLAM maps pockets of up to 4 cells saved no more vertices than up to 2, and up
// to 64 cost more than they saved (docs/results.md, "Wall pockets").
inline constexpr int kMaxWallPocketCells = 2;

// Raster indices of the cells of every wall pocket that lie in the rectangle grown by one cell,
// in row-major order. Uses and clears CellRaster::kVisited.
std::vector<int> WallPocketCells(CellRaster& raster);

}  // namespace fleetmap::vector_map
