#pragma once

// Vector map -> three-state occupancy grid of a given geometry (ALGORITHMS.md 1):
//  - occupied (100): cells whose centre lies within the polyline's radius of one of its edges (or
//    of its point). The radius is max(Polyline::half_width, min_half_width), so a wall comes back
//    at the thickness the vectorizer measured; min_half_width defaults to half a cell, the
//    smallest radius that still gives an unbroken 8-connected line of cells along any edge.
//    We chose the centre-distance rule over "cells a segment crosses": it is symmetric about the
//    edge and does not depend on how a segment meets the cell corners. The old rule (one radius
//    for every edge, epsilon / 2 by default) stays available: use_half_width = false;
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
  // Radius per polyline: max(half_width, min_half_width).
  bool use_half_width = true;
  // Metres; <= 0 takes half the grid resolution.
  double min_half_width = 0.0;
  // With use_half_width = false: one radius for every edge, metres; <= 0 takes the map's
  // epsilon / 2 (the rule before half widths existed).
  double occupied_radius = 0.0;
};

class Rasterizer {
 public:
  explicit Rasterizer(RasterizerOptions options = {}) : options_(std::move(options)) {}

  // Errors (kInvalidArgument): negative size, non-positive resolution, no radius available (the
  // fixed rule on a map without epsilon).
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
