#include "common/vector_map/half_width.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

namespace {

// Per-cell nearest distances, kept per thread between calls and restored to "none" after use.
std::vector<float>& NoDistances(size_t size) {
  thread_local std::vector<float> distances;
  if (distances.size() < size) distances.resize(size, -1.0f);
  return distances;
}

}  // namespace

std::vector<double> CoveredHalfWidths(const CellRaster& raster,
                                      const std::vector<CellPolyline>& polylines, double epsilon,
                                      double min_half_width) {
  const CellRect& rect = raster.rect();
  const double eps2 = ToleratedSquare(epsilon);
  // best[i] < 0: no polyline within epsilon yet; owner is only read where best >= 0.
  std::vector<float>& best = NoDistances(raster.size());
  thread_local std::vector<int> owner;
  if (owner.size() < raster.size()) owner.resize(raster.size());
  std::vector<int> touched;
  auto visit = [&](int polyline, const Point2& a, const Point2& b) {
    ForEachCellNearSegment(a, b, epsilon, [&](int x, int y) {
      if (!rect.Contains(x, y)) return;
      const int i = raster.Index(x, y);
      const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
      if (d2 > eps2) return;
      if (best[i] < 0.0f) {
        touched.push_back(i);
      } else if (static_cast<double>(best[i]) <= d2) {
        return;
      }
      best[i] = static_cast<float>(d2);
      owner[i] = polyline;
    });
  };
  for (size_t p = 0; p < polylines.size(); ++p) {
    const auto& pts = polylines[p].points;
    const int id = static_cast<int>(p);
    if (pts.size() == 1) visit(id, pts[0], pts[0]);
    for (size_t k = 0; k + 1 < pts.size(); ++k) visit(id, pts[k], pts[k + 1]);
    if (polylines[p].closed && pts.size() >= 3) visit(id, pts.back(), pts.front());
  }
  // (polyline, distance, +1 occupied / -1 not) for the cells beyond the minimum radius.
  struct Cell {
    int polyline;
    float d2;
    int gain;
  };
  std::vector<Cell> cells;
  const double min2 = ToleratedSquare(min_half_width);
  for (const int i : touched) {
    if (static_cast<double>(best[i]) > min2) {
      cells.push_back({owner[i], best[i], raster.Has(i, CellRaster::kOccupied) ? 1 : -1});
    }
    best[i] = -1.0f;
  }
  std::sort(cells.begin(), cells.end(), [](const Cell& l, const Cell& r) {
    return l.polyline != r.polyline ? l.polyline < r.polyline : l.d2 < r.d2;
  });
  std::vector<double> half_widths(polylines.size(), 0.0);
  for (size_t begin = 0; begin < cells.size();) {
    size_t end = begin;
    int sum = 0;
    int best_sum = 0;
    double best_d2 = 0.0;
    while (end < cells.size() && cells[end].polyline == cells[begin].polyline) {
      sum += cells[end].gain;
      // Ties at one distance are decided together (a radius takes all of them or none).
      const bool last_at_distance =
          end + 1 == cells.size() || cells[end + 1].polyline != cells[begin].polyline ||
          cells[end + 1].d2 != cells[end].d2;
      if (last_at_distance && sum > best_sum) {
        best_sum = sum;
        best_d2 = cells[end].d2;
      }
      ++end;
    }
    // Rounded up by a float ulp or so: the radius must not fall short of the cells it chose.
    half_widths[cells[begin].polyline] =
        std::min(epsilon, std::sqrt(best_d2) * (1.0 + 1e-6));
    begin = end;
  }
  return half_widths;
}

}  // namespace fleetmap::vector_map
