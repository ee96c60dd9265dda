#pragma once

// Small read-only queries on a local occupancy grid that the extrapolation needs: the state at a
// map-frame point, line of sight, the distance to the nearest obstacle along a ray, and which side
// of a door or a person the map knows more about.
//
// Thread-safety: stateless.

#include <optional>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

// The state of the cell holding `map_point`; kUnknown outside the grid.
grid::CellState StateAtPoint(const grid::OccupancyGrid& map, const Point2& map_point);

// True if no occupied cell lies on the cell line (Bresenham, end cells included) from `a` to `b`.
// Parts outside the grid count as clear.
bool LineOfSight(const grid::OccupancyGrid& map, const Point2& a, const Point2& b);

// Distance (metres) from `origin` along `direction` (unit) to the first occupied cell, marching in
// half-cell steps up to `max_range`; nothing if none.
std::optional<double> DistanceToObstacle(const grid::OccupancyGrid& map, const Point2& origin,
                                         const Vector2& direction, double max_range);

// The dominant side of a person (-1 left, +1 right): the side where obstacles are nearer on
// average along the track, searched up to `search` metres sideways. Nothing if no obstacle is
// found on either side.
std::optional<int> InferDominantSide(const grid::OccupancyGrid& map,
                                     const scene::PersonTrack& track, double search);

// The unit normal of a door line pointing to the side the map has seen less of (fewer free
// cells in a box one door width deep): the side behind a closed door. Nothing if both sides look
// the same.
std::optional<Vector2> InferOpeningDirection(const grid::OccupancyGrid& map,
                                             const scene::DoorEntity& door);

}  // namespace fleetmap::extrapolation
