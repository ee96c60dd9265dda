#pragma once

// Splits a changed region that is too large to be one object (a row of desks, a table with its
// chairs) into parts that are (issue 22). Large regions used to be dropped with a warning, which
// lost every object in them. In order, until each part is small enough:
//  1. the parts that do not touch at all (8-connected; region growing links cells up to
//     link_cells apart, which joins nearby objects);
//  2. the parts joined by narrow necks: the region is eroded until it falls apart, and the cores
//     left seed a geodesic watershed (each cell goes to the core that reaches it first inside
//     the region), so every cell stays in some part;
//  3. slices across the part's long axis, as many as needed: a solid block of furniture has no
//     neck to cut at, and a slice of it is a better snapshot than nothing (a warning says so).
//
// Thread-safety: stateless.

#include <vector>

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::object_learning {

struct RegionLimits {
  int max_cells = 4000;
  int max_radius_cells = 30;  // from the region's centroid cell to its farthest cell
};

struct SplitRegions {
  std::vector<std::vector<grid::CellIndex>> parts;
  bool sliced = false;  // step 3 was needed for some part
};

// The farthest cell of `cells` from their (rounded) centroid cell, in cells.
double RegionRadius(const std::vector<grid::CellIndex>& cells);

// `cells` split until every part is within `limits` (parts keep every input cell once).
SplitRegions SplitRegion(const std::vector<grid::CellIndex>& cells, const RegionLimits& limits);

}  // namespace fleetmap::object_learning
