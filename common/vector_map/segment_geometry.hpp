#pragma once

// Exact geometry of segments against cell centres, in cell coordinates (see CellFrame). Shared by
// the vectorizer (which must guarantee the constraints), the validator (which checks them) and the
// rasterizer. Comparisons against epsilon allow a relative slack of kDistanceTolerance so that a
// point at exactly epsilon (a diagonal neighbour at the default sqrt(2) * res) counts as within.

#include <algorithm>
#include <cmath>

#include "common/core/types.hpp"
#include "common/vector_map/delimitation.hpp"

namespace fleetmap::vector_map {

inline constexpr double kDistanceTolerance = 1e-9;

// epsilon^2 with the tolerance applied; compare squared distances against this.
inline double ToleratedSquare(double distance) {
  return distance * distance * (1.0 + kDistanceTolerance) + kDistanceTolerance;
}

double PointSegmentDistanceSquared(const Point2& p, const Point2& a, const Point2& b);

// Calls f(x, y) for every integer cell (x, y) whose centre may lie within `radius` of segment
// [a, b] (a superset: a band about 2 * radius + 3 cells wide along the segment; never misses one).
// Callers test the exact distance themselves. A degenerate segment (a == b) is a point.
template <typename F>
void ForEachCellNearSegment(const Point2& a, const Point2& b, double radius, F&& f) {
  constexpr double kSlack = 1e-7;
  const double dx = b.x() - a.x();
  const double dy = b.y() - a.y();
  const bool along_x = std::abs(dx) >= std::abs(dy);
  // Iterate the major axis (u) and, per major coordinate, the minor range (v) the band needs.
  const double au = along_x ? a.x() : a.y();
  const double av = along_x ? a.y() : a.x();
  const double du = along_x ? dx : dy;
  const double dv = along_x ? dy : dx;
  const int u_min = static_cast<int>(std::ceil(std::min(au, au + du) - radius - kSlack));
  const int u_max = static_cast<int>(std::floor(std::max(au, au + du) + radius + kSlack));
  for (int u = u_min; u <= u_max; ++u) {
    double v_lo = av;
    double v_hi = av;
    if (du != 0.0) {
      double t0 = (u - radius - au) / du;
      double t1 = (u + radius - au) / du;
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::clamp(t0, 0.0, 1.0);
      t1 = std::clamp(t1, 0.0, 1.0);
      v_lo = std::min(av + t0 * dv, av + t1 * dv);
      v_hi = std::max(av + t0 * dv, av + t1 * dv);
    }
    const int v_min = static_cast<int>(std::ceil(v_lo - radius - kSlack));
    const int v_max = static_cast<int>(std::floor(v_hi + radius + kSlack));
    for (int v = v_min; v <= v_max; ++v) {
      if (along_x) {
        f(u, v);
      } else {
        f(v, u);
      }
    }
  }
}

// The continuity constraint for one segment, decided exactly: is every point of [a, b] within
// `epsilon` of some delimitation point? Computes, for each delimitation point near the segment,
// the interval of the segment inside its epsilon-disc, and checks that their union covers [a, b].
bool SegmentContinuous(const Point2& a, const Point2& b, double epsilon,
                       const Delimitation& delimitation);

// The largest distance from a point of [a, b] to its nearest delimitation point, computed on
// samples `step` apart (cell units) with the nearest point searched within `search_radius`
// (beyond it, `search_radius` is returned). Reporting only; decisions use SegmentContinuous.
double SampledMaxDistanceToDelimitation(const Point2& a, const Point2& b,
                                        const Delimitation& delimitation, double search_radius,
                                        double step);

}  // namespace fleetmap::vector_map
