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
                                      const std::vector<CellPolyline>& polylines, double epsilon) {
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
      if (!raster.Has(i, CellRaster::kOccupied)) return;
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
  std::vector<double> half_widths(polylines.size(), 0.0);
  for (const int i : touched) {
    // Rounded up by a float ulp or so: the half width must not fall short of the exact distance.
    const double d = std::sqrt(static_cast<double>(best[i])) * (1.0 + 1e-6);
    double& h = half_widths[owner[i]];
    h = std::max(h, std::min(epsilon, d));
    best[i] = -1.0f;
  }
  return half_widths;
}

}  // namespace fleetmap::vector_map
