#pragma once

// Topological places of the observed map (ALGORITHMS.md 3: sub-maps not separated by a door or
// stairs belong to the same place). The free cells are cut along each door (hinge to latch, open
// or closed) and across the foot of each flight of stairs; the 4-connected components of what
// remains are the places (docs/extrapolation.md, "Places").
//
// 4-connectivity, not 8: a laser map's diagonal wall is often an 8-connected line of occupied
// cells, which 8-connected free space would cross. A cut is the segment rasterised (samples every
// quarter cell) and dilated by one cell (3 x 3), so it is at least two cells thick and stays
// closed whatever its angle.
//
// Thread-safety: stateless.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::extrapolation {

// A separator in the map frame (metres): a door's hinge-latch segment, the foot of a flight.
struct PlaceCut {
  Point2 a = Point2::Zero();
  Point2 b = Point2::Zero();
};

// Per cell of the map (row-major), the place it belongs to, or -1 (not free, or dropped).
struct PlacePartition {
  int width = 0;
  int height = 0;
  int place_count = 0;
  std::vector<int32_t> labels;

  int32_t Label(int x, int y) const { return labels[static_cast<size_t>(y) * width + x]; }
};

// `free` is row-major with the map's size: the cells to partition (the local map's free cells and
// the people's conditionally free ones).
//
// - The components of the free cells off the cuts (the cores) that have at least `min_place_cells`
//   cells are the places, numbered in row-major order of their first cell (y, then x, from the
//   map's origin corner). If none is that large, the largest is a place (the first on ties), so a
//   map with free cells has at least one place.
// - Every other free cell (on a cut, or in a smaller core: speckle, a corner cut off by a door's
//   jamb) joins the place it is nearest to in 4-connected steps through free cells; a cell as
//   near to two places joins the lower-numbered one. Free cells that reach no place (isolated
//   speckle) are in no place (-1).
PlacePartition PartitionPlaces(const grid::OccupancyGrid& map, const std::vector<uint8_t>& free,
                               const std::vector<PlaceCut>& cuts, int64_t min_place_cells);

// The place most of the cells within `depth` (metres) of the segment a-b on the side `side`
// points to belong to (ties: the lower place), or nullopt if none of them is in a place.
std::optional<int32_t> PlaceBeside(const grid::OccupancyGrid& map, const PlacePartition& places,
                                   const Point2& a, const Point2& b, const Vector2& side,
                                   double depth);

// The place of the labelled cell nearest to `p` (ties: the first in row-major order), or
// nullopt if there is no place.
std::optional<int32_t> NearestPlace(const grid::OccupancyGrid& map, const PlacePartition& places,
                                    const Point2& p);

}  // namespace fleetmap::extrapolation
