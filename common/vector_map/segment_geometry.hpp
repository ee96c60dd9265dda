#pragma once

// Exact geometry of segments against cell centres, in cell coordinates (see CellFrame). Shared by
// the vectorizer (which must guarantee the constraints), the validator (which checks them) and the
// rasterizer. Comparisons against epsilon allow a relative slack of kDistanceTolerance so that a
// point at exactly epsilon (a diagonal neighbour at the default sqrt(2) * res) counts as within.

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "common/core/types.hpp"
#include "common/vector_map/delimitation.hpp"

namespace fleetmap::vector_map {

inline constexpr double kDistanceTolerance = 1e-9;

// epsilon^2 with the tolerance applied; compare squared distances against this.
inline double ToleratedSquare(double distance) {
  return distance * distance * (1.0 + kDistanceTolerance) + kDistanceTolerance;
}

// Inline: it runs per cell in the inner loops of the vectorizer and the half widths.
inline double PointSegmentDistanceSquared(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double length_squared = ab.squaredNorm();
  if (length_squared == 0.0) return (p - a).squaredNorm();
  const double t = std::clamp((p - a).dot(ab) / length_squared, 0.0, 1.0);
  return (p - (a + t * ab)).squaredNorm();
}

// Calls f(x, y) for every integer cell (x, y) whose centre may lie within `radius` of segment
// [a, b] (a superset: a band about 2 * radius + 3 cells wide along the segment; never misses one).
// Callers test the exact distance themselves. A degenerate segment (a == b) is a point.
template <typename F>
void ForEachCellNearSegment(const Point2& a, const Point2& b, double radius, F&& f);

// The same cells, in the same order, restricted to those inside `clip`: the band is clipped per
// row, so a caller that would skip cells outside a rectangle pays no bounds test per cell.
template <typename F>
void ForEachCellNearSegmentIn(const grid::CellRect& clip, const Point2& a, const Point2& b,
                              double radius, F&& f);

// The continuity constraint for one segment, decided exactly: is every point of [a, b] within
// `epsilon` of some delimitation point? Computes, for each delimitation point near the segment,
// the interval of the segment inside its epsilon-disc, and checks that their union covers [a, b].
// `is_delimitation(x, y)` says whether cell (x, y) is in P (it must be safe for any cell).
template <typename IsDelimitation>
bool SegmentContinuousIf(const Point2& a, const Point2& b, double epsilon,
                         IsDelimitation&& is_delimitation);

bool SegmentContinuous(const Point2& a, const Point2& b, double epsilon,
                       const Delimitation& delimitation);

// The largest distance from a point of [a, b] to its nearest delimitation point, computed on
// samples `step` apart (cell units) with the nearest point searched within `search_radius`
// (beyond it, `search_radius` is returned). Reporting only; decisions use SegmentContinuous.
double SampledMaxDistanceToDelimitation(const Point2& a, const Point2& b,
                                        const Delimitation& delimitation, double search_radius,
                                        double step);

// Implementation ---------------------------------------------------------------------------------

namespace segment_geometry_detail {

// static_cast<int>(std::ceil(v)) and static_cast<int>(std::floor(v)) for v in the int range,
// without the libm calls (x86-64 without SSE4.1 has no rounding instruction).
inline int CeilToInt(double v) {
  const int i = static_cast<int>(v);  // toward zero
  return i < v ? i + 1 : i;
}
inline int FloorToInt(double v) {
  const int i = static_cast<int>(v);
  return i > v ? i - 1 : i;
}

// ForEachCellNearSegment's cells with x in [x_lo, x_hi] and y in [y_lo, y_hi].
template <typename F>
void ForEachCellNearSegmentClipped(const Point2& a, const Point2& b, double radius, int x_lo,
                                   int x_hi, int y_lo, int y_hi, F&& f) {
  constexpr double kSlack = 1e-7;
  const double dx = b.x() - a.x();
  const double dy = b.y() - a.y();
  const bool along_x = std::abs(dx) >= std::abs(dy);
  // Iterate the major axis (u) and, per major coordinate, the minor range (v) the band needs.
  const double au = along_x ? a.x() : a.y();
  const double av = along_x ? a.y() : a.x();
  const double du = along_x ? dx : dy;
  const double dv = along_x ? dy : dx;
  const int u_lo = along_x ? x_lo : y_lo;
  const int u_hi = along_x ? x_hi : y_hi;
  const int clip_v_lo = along_x ? y_lo : x_lo;
  const int clip_v_hi = along_x ? y_hi : x_hi;
  const int u_min = std::max(CeilToInt(std::min(au, au + du) - radius - kSlack), u_lo);
  const int u_max = std::min(FloorToInt(std::max(au, au + du) + radius + kSlack), u_hi);
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
    const int v_min = std::max(CeilToInt(v_lo - radius - kSlack), clip_v_lo);
    const int v_max = std::min(FloorToInt(v_hi + radius + kSlack), clip_v_hi);
    // The axis test per row, not per cell.
    if (along_x) {
      for (int v = v_min; v <= v_max; ++v) f(u, v);
    } else {
      for (int v = v_min; v <= v_max; ++v) f(v, u);
    }
  }
}

}  // namespace segment_geometry_detail

template <typename F>
void ForEachCellNearSegment(const Point2& a, const Point2& b, double radius, F&& f) {
  constexpr int kMin = std::numeric_limits<int>::min();
  constexpr int kMax = std::numeric_limits<int>::max();
  segment_geometry_detail::ForEachCellNearSegmentClipped(a, b, radius, kMin, kMax, kMin, kMax, f);
}

template <typename F>
void ForEachCellNearSegmentIn(const grid::CellRect& clip, const Point2& a, const Point2& b,
                              double radius, F&& f) {
  segment_geometry_detail::ForEachCellNearSegmentClipped(
      a, b, radius, clip.x0, clip.x0 + clip.width - 1, clip.y0, clip.y0 + clip.height - 1, f);
}

// True if the sorted intervals cover [0, length] (gaps up to the distance tolerance allowed).
bool IntervalsCover(std::vector<std::pair<double, double>>& intervals, double length);

template <typename IsDelimitation>
bool SegmentContinuousIf(const Point2& a, const Point2& b, double epsilon,
                         IsDelimitation&& is_delimitation) {
  const double eps2 = ToleratedSquare(epsilon);
  const double length = (b - a).norm();
  if (length < kDistanceTolerance) {
    bool found = false;
    ForEachCellNearSegment(a, a, epsilon, [&](int x, int y) {
      if (!found && is_delimitation(x, y) && (Point2(x, y) - a).squaredNorm() <= eps2) {
        found = true;
      }
    });
    return found;
  }
  const double ux = (b.x() - a.x()) / length;
  const double uy = (b.y() - a.y()) / length;
  thread_local std::vector<std::pair<double, double>> intervals;
  intervals.clear();
  ForEachCellNearSegment(a, b, epsilon, [&](int x, int y) {
    if (!is_delimitation(x, y)) return;
    const double wx = x - a.x();
    const double wy = y - a.y();
    const double along = wx * ux + wy * uy;
    const double across2 = wx * wx + wy * wy - along * along;
    const double half2 = eps2 - across2;
    if (half2 < 0.0) return;
    const double half = std::sqrt(half2);
    if (along + half < 0.0 || along - half > length) return;
    intervals.emplace_back(along - half, along + half);
  });
  return IntervalsCover(intervals, length);
}

}  // namespace fleetmap::vector_map
