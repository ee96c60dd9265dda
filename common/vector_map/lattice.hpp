#pragma once

// Coordinate quantisation (VectorizerOptions::quantum): a vertex snapped to the lattice
// origin + k * quantum (k integer per axis, map frame) moves by at most quantum * sqrt(2) / 2.
// Unless the lattice holds every half-cell point of the grid, the vectorizer builds with epsilon
// reduced by that much, so both constraints still hold after snapping (a snapped segment is within
// that distance of the unsnapped one, point by point).
// Snapping is a deterministic function of the point, so tiles that compute the same border node
// snap it to the same lattice point.

#include "common/core/types.hpp"

namespace fleetmap::vector_map {

class Lattice {
 public:
  // quantum <= 0: no snapping.
  Lattice(double quantum, const Point2& origin) : quantum_(quantum), origin_(origin) {}

  bool enabled() const { return quantum_ > 0.0; }
  double quantum() const { return quantum_; }
  // The largest distance Snap() moves a point.
  double MaxDisplacement() const;
  Point2 Snap(const Point2& p) const;
  // Whether `p` lies on the lattice (within a millionth of a quantum; Snap then moves it by far
  // less than the vectorizer's distance tolerance).
  bool Contains(const Point2& p) const;

 private:
  double quantum_;
  Point2 origin_;
};

}  // namespace fleetmap::vector_map
