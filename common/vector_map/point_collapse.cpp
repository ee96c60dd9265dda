#include "common/vector_map/point_collapse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "common/vector_map/half_width.hpp"
#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

constexpr double kMinHalfWidth = 0.5;  // cells: the Rasterizer paints at least this far

double PolylineLength(const std::vector<Point2>& points) {
  double length = 0.0;
  for (size_t k = 0; k + 1 < points.size(); ++k) length += (points[k + 1] - points[k]).norm();
  return length;
}

// Whether some P point (owned or not) lies within epsilon of `c`: a point obstacle's continuity.
bool NearDelimitation(const CellRaster& raster, const Point2& c, double epsilon) {
  const double eps2 = ToleratedSquare(epsilon);
  const int r = static_cast<int>(std::ceil(epsilon)) + 1;
  const int cx = static_cast<int>(std::lround(c.x()));
  const int cy = static_cast<int>(std::lround(c.y()));
  for (int y = cy - r; y <= cy + r; ++y) {
    for (int x = cx - r; x <= cx + r; ++x) {
      if (raster.IsDelimitation(x, y) && (Point2(x, y) - c).squaredNorm() <= eps2) return true;
    }
  }
  return false;
}

}  // namespace

void CollapseToPoints(CellRaster& raster, double epsilon, std::vector<CellPolyline>& polylines) {
  const double eps2 = ToleratedSquare(epsilon);
  const CellRect window = raster.window();
  std::vector<Point2> covered;
  std::vector<CellPolyline> drawing(1);
  std::vector<std::pair<double, Point2>> valid;  // (squared reach, candidate)
  for (CellPolyline& polyline : polylines) {
    const std::vector<Point2>& pts = polyline.points;
    if (pts.size() < 2 || polyline.closed || polyline.start_on_border || polyline.end_on_border ||
        PolylineLength(pts) > 2.0 * epsilon) {
      continue;
    }
    covered.clear();  // the owned P points within epsilon of the polyline
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      ForEachCellNearSegmentIn(window, pts[k], pts[k + 1], epsilon, [&](int x, int y) {
        if (!raster.Has(raster.Index(x, y), CellRaster::kOwned)) return;
        const Point2 p(x, y);
        if (PointSegmentDistanceSquared(p, pts[k], pts[k + 1]) > eps2) return;
        if (k > 0 && PointSegmentDistanceSquared(p, pts[k - 1], pts[k]) <= eps2) return;
        covered.push_back(p);
      });
    }
    if (covered.empty()) continue;
    Point2 centroid = Point2::Zero();
    for (const Point2& p : covered) centroid += p;
    centroid /= static_cast<double>(covered.size());
    // On half cells, which are lattice points whenever cell centres are (lattice.hpp).
    auto on_half_cells = [](const Point2& p) {
      return Point2(std::round(2.0 * p.x()) / 2.0, std::round(2.0 * p.y()) / 2.0);
    };
    const std::array<Point2, 4> candidates = {on_half_cells(centroid), pts.front(), pts.back(),
                                              on_half_cells(0.5 * (pts.front() + pts.back()))};
    // The geometric tests first: the paint match is the costly one.
    valid.clear();
    for (const Point2& c : candidates) {
      double reach = 0.0;
      for (const Point2& p : covered) reach = std::max(reach, (p - c).squaredNorm());
      const bool seen =
          std::any_of(valid.begin(), valid.end(), [&](const auto& v) { return v.second == c; });
      if (!seen && reach <= eps2 && NearDelimitation(raster, c, epsilon)) {
        valid.emplace_back(reach, c);
      }
    }
    if (valid.empty()) continue;
    std::stable_sort(valid.begin(), valid.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    drawing[0] = polyline;
    int best_score = PaintMatch(raster, drawing, epsilon, kMinHalfWidth);  // to paint as well
    const Point2* chosen = nullptr;
    for (const auto& [reach, c] : valid) {  // nearest reach first: it wins ties
      drawing[0].points.assign(1, c);
      const int score = PaintMatch(raster, drawing, epsilon, kMinHalfWidth);
      if (score < best_score || (score == best_score && chosen != nullptr)) continue;
      best_score = score;
      chosen = &c;
    }
    if (chosen != nullptr) polyline.points.assign(1, *chosen);
  }
}

}  // namespace fleetmap::vector_map
