#pragma once

// The cells of a rectangle that the Rasterizer will paint occupied for a set of polylines (cell
// coordinates, CellFrame): cells whose centre lies within max(radius, min_radius) of an edge or
// point of the polyline. The free-space extractor treats them as "don't care" (the rasterizer
// paints obstacles over free space), so a free outline need not follow a wall it runs along.

#include <cstdint>
#include <vector>

#include "common/grid/cell_rect.hpp"
#include "common/vector_map/cell_polyline.hpp"

namespace fleetmap::vector_map {

// One byte per cell of `rect`, row-major, 1 where painted. `radii[k]` is polyline k's half width
// in cells (empty: min_radius for every polyline). The test is a hair stricter than the
// rasterizer's tolerated radius (never marks a cell the rasterizer could leave unpainted after a
// round trip through the wire's quantised half widths, which only grow) but counts the cells at
// exactly the radius.
std::vector<uint8_t> PaintedCells(const grid::CellRect& rect,
                                  const std::vector<CellPolyline>& polylines,
                                  const std::vector<double>& radii, double min_radius);

// PaintedCells(rect, polylines, radii, min_radius) into `painted` and, from the same visit of each
// segment's band, PaintedCells(rect, polylines, {}, near_radius) into `near` (the free-space
// extractor's two masks), bit for bit. Both are resized to the rectangle; their storage is reused.
void PaintedAndNearCells(const grid::CellRect& rect, const std::vector<CellPolyline>& polylines,
                         const std::vector<double>& radii, double min_radius, double near_radius,
                         std::vector<uint8_t>* painted, std::vector<uint8_t>* near);

}  // namespace fleetmap::vector_map
