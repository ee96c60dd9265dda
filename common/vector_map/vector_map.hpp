#pragma once

// The in-memory vector map: obstacle polylines and explored free space in the map frame (metres).
// Deliberately plain (vectors of points) so that the DDS codec can turn it into a
// structure-of-arrays tile without knowing anything about how it was made. docs/vector-maps.md
// explains the constraints a vector map made by the Vectorizer satisfies.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::vector_map {

// An obstacle boundary as a chain of vertices; each consecutive pair is one segment (an edge of
// the paper's graph). `closed` adds the segment from the last vertex back to the first. A polyline
// with a single vertex is a point obstacle (a zero-length segment, e.g. an isolated occupied cell).
struct Polyline {
  std::vector<Point2> points;
  bool closed = false;
  // Metres, in [0, epsilon]: the obstacle cells this polyline stands for lie within half_width of
  // it, so the rasterizer can give a thick wall back its thickness.
  double half_width = 0.0;

  // Segments it stands for: 0 for a point, n - 1 open, n closed (n >= 3).
  size_t SegmentCount() const;
  friend bool operator==(const Polyline&, const Polyline&) = default;
};

// Explored free space: a simple outer ring (not repeated at the end) with simple holes.
struct FreePolygon {
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> holes;
  friend bool operator==(const FreePolygon&, const FreePolygon&) = default;
};

// The lattice a map's vertices lie on: origin + (i, j) * quantum for whole i, j (metres, in the
// map's frame). A quantum of 0 means none: vertices anywhere. The tile codec sends vertices as
// whole steps of the lattice (tiled_vector_map.hpp says which lattice the tiles use).
struct VertexLattice {
  double quantum = 0.0;
  Point2 origin = Point2::Zero();

  bool enabled() const { return quantum > 0.0; }
  friend bool operator==(const VertexLattice&, const VertexLattice&) = default;
};

struct VectorMap {
  std::string frame_id = "map";
  double resolution = 0.05;  // of the grid it was made from (metres per cell)
  double epsilon = 0.0;      // the error bound both constraints were built with (metres)
  VertexLattice lattice;     // the vectorizer's, when it snapped vertices to one
  std::vector<Polyline> obstacles;
  std::vector<FreePolygon> free_space;

  // Sum of the obstacle polylines' vertex counts (a vertex shared by two polylines counts twice,
  // as it is stored twice).
  size_t ObstacleVertexCount() const;
  size_t ObstacleSegmentCount() const;
  size_t FreeVertexCount() const;

  // Appends another map's geometry (e.g. the tiles of one grid into one map); the lattice stays
  // this map's.
  void Append(const VectorMap& other);
};

// The map's geometry carried into another frame by a rigid transform (p_to = to_from_map * p).
// Lengths are kept, so half widths and epsilon still hold; the vertices leave the lattice, so the
// result has none.
VectorMap Transformed(const VectorMap& map, const Transform2& to_from_map, std::string frame_id);

// The axis-aligned box (min, max corners) that holds the map's geometry, obstacles grown by their
// half widths; nullopt for a map without geometry.
std::optional<std::pair<Point2, Point2>> Bounds(const VectorMap& map);

// sqrt(2) * resolution: the smallest distance joining a cell centre to its 8 neighbours.
double DefaultEpsilon(double resolution);

// Half widths travel in the tile codec as uint8 counts of HalfWidthStep(epsilon): epsilon (as the
// tile's float field holds it) / 254. So 254 steps make epsilon and the 255th absorbs the float's
// rounding: a half width of exactly epsilon always fits. At the default epsilon of a 5 cm grid a
// step is 0.28 mm.
inline constexpr int kHalfWidthStepsPerEpsilon = 254;
inline constexpr int kMaxHalfWidthSteps = 255;
double HalfWidthStep(double epsilon);

}  // namespace fleetmap::vector_map
