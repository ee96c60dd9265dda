#include "common/vector_map/half_width.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

std::vector<double> CoveredHalfWidths(const CellRaster& raster,
                                      const std::vector<CellPolyline>& polylines, double epsilon) {
  const auto& occupied = raster.occupied_near_rect();  // sorted raster indices
  const CellRect& rect = raster.rect();
  const double eps2 = ToleratedSquare(epsilon);
  std::vector<double> best(occupied.size(), std::numeric_limits<double>::infinity());
  std::vector<int> owner(occupied.size(), -1);
  auto visit = [&](int polyline, const Point2& a, const Point2& b) {
    ForEachCellNearSegment(a, b, epsilon, [&](int x, int y) {
      if (!rect.Contains(x, y)) return;
      const int i = raster.Index(x, y);
      if (!raster.Has(i, CellRaster::kOccupied)) return;
      const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
      if (d2 > eps2) return;
      const size_t k = static_cast<size_t>(
          std::lower_bound(occupied.begin(), occupied.end(), i) - occupied.begin());
      if (d2 < best[k]) {
        best[k] = d2;
        owner[k] = polyline;
      }
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
  for (size_t k = 0; k < occupied.size(); ++k) {
    if (owner[k] < 0) continue;
    double& h = half_widths[owner[k]];
    h = std::max(h, std::min(epsilon, std::sqrt(best[k])));
  }
  return half_widths;
}

}  // namespace fleetmap::vector_map
