#pragma once

// PNG pictures of grids and vector maps. Images are upright (the map frame's y axis points up, so
// grid row 0 is the image's bottom row, as in map_server files).

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

// 8-bit grey in map_server's trinary shades: occupied 0, free 254, unknown 205.
StatusOr<std::vector<uint8_t>> EncodeGridPng(const grid::OccupancyGrid& grid);

struct VectorPngOptions {
  int pixels_per_cell = 2;
  bool draw_vertices = true;
};

// Draws the map over the geometry of `like` (size, resolution, origin): free space light, unknown
// mid grey, obstacle polylines dark, vertices red. Colour PNG.
StatusOr<std::vector<uint8_t>> RenderVectorMapPng(const VectorMap& map,
                                                  const grid::OccupancyGrid& like,
                                                  const VectorPngOptions& options = {});

}  // namespace fleetmap::vector_map
