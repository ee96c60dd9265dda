#include "common/vector_map/painted_cells.hpp"

#include <algorithm>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

std::vector<uint8_t> PaintedCells(const grid::CellRect& rect,
                                  const std::vector<CellPolyline>& polylines,
                                  const std::vector<double>& radii, double min_radius) {
  std::vector<uint8_t> painted(static_cast<size_t>(rect.width) * rect.height, 0);
  if (rect.empty()) return painted;
  double r2 = 0.0;
  auto mark = [&](const Point2& a, const Point2& b, double r) {
    ForEachCellNearSegment(a, b, r, [&](int x, int y) {
      if (!rect.Contains(x, y)) return;
      if (PointSegmentDistanceSquared(Point2(x, y), a, b) <= r2) {
        painted[static_cast<size_t>(y - rect.y0) * rect.width + (x - rect.x0)] = 1;
      }
    });
  };
  for (size_t k = 0; k < polylines.size(); ++k) {
    const auto& pts = polylines[k].points;
    const double r = std::max(radii.empty() ? 0.0 : radii[k], min_radius);
    // The radius itself (cells at exactly it, e.g. the corner cells of a block, are painted and
    // must count, or the free-space extractor guards them as solid), with a relative 1e-10 for
    // rounding: a tenth of the rasterizer's tolerance (ToleratedSquare), which is still far above
    // the float noise after decoding (about 1e-12 cells, another frame); quantised half widths
    // only grow. So no marked cell is left unpainted.
    r2 = r * r * (1.0 + 1e-10);
    if (pts.size() == 1) mark(pts[0], pts[0], r);
    for (size_t i = 0; i + 1 < pts.size(); ++i) mark(pts[i], pts[i + 1], r);
    if (polylines[k].closed && pts.size() >= 3) mark(pts.back(), pts.front(), r);
  }
  return painted;
}

}  // namespace fleetmap::vector_map
