#pragma once

// Thinning of the occupied cells of a CellRaster's rectangle to a one-cell skeleton that never
// leaves the obstacle boundary it stands for (docs/vector-maps.md, kDefault steps 1-2).
//
// Hollowing keeps only occupied cells that are in P or 4-adjacent to P (thick blobs become rings
// two cells wide, so the work is proportional to the boundary). Directional sequential thinning
// (N, S, E, W passes) then deletes simple points (from a 256-entry table) and line ends, but only
// if every P point of the rectangle within epsilon of the pixel keeps another skeleton pixel within
// epsilon. A wall up to about 2 epsilon thick becomes one centre line; occupied cells just outside
// the rectangle are fixed anchors, so skeletons run up to the tile border.

#include <array>
#include <vector>

#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

// The 8 neighbours in cyclic order: E, NE, N, NW, W, SW, S, SE.
inline constexpr std::array<int, 8> kNeighbourDx = {1, 1, 0, -1, -1, -1, 0, 1};
inline constexpr std::array<int, 8> kNeighbourDy = {0, 1, 1, 1, 0, -1, -1, -1};

// table[mask]: deleting a pixel whose foreground 8-neighbourhood is `mask` (bit k = neighbour k)
// keeps the topology (one 8-connected foreground component around it, one 4-connected background
// component touching it) and does not shorten a line (at least two neighbours).
const std::array<bool, 256>& SimplePointTable();

// Sets CellRaster::kSkeleton on the skeleton pixels and kAnchor on occupied cells just outside the
// rectangle; returns the skeleton pixels (raster indices, row-major). `epsilon` in cells.
std::vector<int> ThinToSkeleton(CellRaster& raster, double epsilon);

// Raster-index offsets of the cells within `epsilon` (cells) of a cell, nearest first (ties in a
// fixed order), the cell itself included.
std::vector<int> DiscOffsets(const CellRaster& raster, double epsilon);

}  // namespace fleetmap::vector_map
