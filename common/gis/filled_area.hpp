#pragma once

// The area fleetmap fills from a set of rings, as valid OGC simple features.
//
// fleetmap's rings (a vector map's free polygon, the outlines of a grid's free cells) pass through
// cell centres and mean what the rasterizer fills from them: every point inside an odd number of
// rings (even-odd rule, so a hole is simply another ring) plus every ring's own outline. A ring of
// one vertex is a point (one free cell), a ring of two a line of cells, and a ring may touch or
// cross itself and its holes. GIS tools want simple features instead: closed rings of at least
// four positions, no self-intersection, holes inside their shell. FilledAreaOfRings gives the
// same point set as such features:
//  - `polygons`: the parts with area, a valid (Multi)Polygon; rings closed (last position repeats
//    the first), shells counter-clockwise and holes clockwise (RFC 7946), no repeated positions;
//  - `lines`: outlines that bound no area (a line of cells, a one-cell-wide spike or corridor);
//  - `points`: one-vertex rings not already on a polygon or line.
// Every coordinate is the double nearest a decimal of `decimals` places (kCoordinateDecimals for
// frame metres), as the GeoJSON exports write it: a vertex on a 0.025 m lattice is 42.175, not the
// 42.175000000000004 binary arithmetic makes of it. Where rounding would make a polygon invalid (a
// sliver a rounding error wide crossing itself, a few in a thousand on real maps vectorized without
// a lattice), that polygon keeps its vertices as they are: valid comes first.
//
// Thread-safety: stateless; concurrent calls are safe (each call has its own GEOS context).

#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"

namespace fleetmap::gis {

// Decimal places of a metre the coordinates are snapped to: a micrometre, finer than any map.
inline constexpr int kCoordinateDecimals = 6;

struct SimplePolygon {
  std::vector<Point2> shell;
  std::vector<std::vector<Point2>> holes;
};

struct FilledArea {
  std::vector<SimplePolygon> polygons;
  std::vector<std::vector<Point2>> lines;
  std::vector<Point2> points;

  bool empty() const { return polygons.empty() && lines.empty() && points.empty(); }
};

// Rings are not closed (the last vertex is not the first again); empty rings are ignored. The
// rings may be in any plane coordinates: frame metres, or longitude and latitude in degrees with
// `decimals` = kDegreeDecimals (georeferenced_geojson.hpp). Errors (kInternal) only if GEOS fails
// on the geometry, with GEOS's message.
StatusOr<FilledArea> FilledAreaOfRings(const std::vector<std::vector<Point2>>& rings,
                                       int decimals = kCoordinateDecimals);

}  // namespace fleetmap::gis
