#pragma once

// Vector map -> three-state occupancy grid of a given geometry (ALGORITHMS.md 1):
//  - occupied (100): cells whose centre lies within `occupied_radius` (default epsilon / 2) of an
//    edge or of a point obstacle. We chose the centre-distance rule over "cells a segment crosses":
//    it is symmetric about the edge and does not depend on how a segment meets the cell corners;
//  - free (0): other cells inside a free polygon (outline included, holes excluded);
//  - unknown (-1): the rest.
//
// Thread-safety: stateless; concurrent calls are safe.

#include <utility>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

struct RasterizerOptions {
  // Metres; <= 0 takes the map's epsilon / 2.
  double occupied_radius = 0.0;
};

class Rasterizer {
 public:
  explicit Rasterizer(RasterizerOptions options = {}) : options_(std::move(options)) {}

  // Errors (kInvalidArgument): negative size, non-positive resolution, no radius available.
  StatusOr<grid::OccupancyGrid> Rasterize(const VectorMap& map, int width, int height,
                                          double resolution, const Pose2& origin) const;
  // Same geometry (size, resolution, origin) as `like`.
  StatusOr<grid::OccupancyGrid> Rasterize(const VectorMap& map,
                                          const grid::OccupancyGrid& like) const {
    return Rasterize(map, like.width(), like.height(), like.resolution(), like.origin());
  }

 private:
  RasterizerOptions options_;
};

}  // namespace fleetmap::vector_map
