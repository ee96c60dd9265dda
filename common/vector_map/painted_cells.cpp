#include "common/vector_map/painted_cells.hpp"

#include <algorithm>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

// The radius itself (cells at exactly it, e.g. the corner cells of a block, are painted and must
// count, or the free-space extractor guards them as solid), with a relative 1e-10 for rounding: a
// tenth of the rasterizer's tolerance (ToleratedSquare), which is still far above the float noise
// after decoding (about 1e-12 cells, another frame); quantised half widths only grow. So no marked
// cell is left unpainted.
double MarkedSquare(double radius) { return radius * radius * (1.0 + 1e-10); }

// Calls visit(a, b, r) for every segment (or point) of polyline k, r its radius.
template <typename Visit>
void ForEachSegment(const CellPolyline& polyline, double r, Visit&& visit) {
  const auto& pts = polyline.points;
  if (pts.size() == 1) visit(pts[0], pts[0], r);
  for (size_t i = 0; i + 1 < pts.size(); ++i) visit(pts[i], pts[i + 1], r);
  if (polyline.closed && pts.size() >= 3) visit(pts.back(), pts.front(), r);
}

}  // namespace

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
    const double r = std::max(radii.empty() ? 0.0 : radii[k], min_radius);
    r2 = MarkedSquare(r);
    ForEachSegment(polylines[k], r, mark);
  }
  return painted;
}

void PaintedAndNearCells(const grid::CellRect& rect, const std::vector<CellPolyline>& polylines,
                         const std::vector<double>& radii, double min_radius, double near_radius,
                         std::vector<uint8_t>* painted, std::vector<uint8_t>* near) {
  const size_t size = static_cast<size_t>(rect.width) * rect.height;
  painted->assign(size, 0);
  near->assign(size, 0);
  if (rect.empty()) return;
  // The near test is PaintedCells' with radius max(0, near_radius) for every polyline.
  const double near_r = std::max(0.0, near_radius);
  const double near2 = MarkedSquare(near_r);
  double r2 = 0.0;
  // One visit of the larger band, clipped to the rectangle: ForEachCellNearSegment's candidates
  // only grow with the radius, so it lists every cell either call would have tested, and each test
  // is the same exact one.
  // Locals only in the cell loop: a byte store may alias anything read through a reference or a
  // member, which would be reloaded for every cell.
  const grid::CellRect bounds = rect;
  uint8_t* const painted_cells = painted->data();
  uint8_t* const near_cells = near->data();
  auto mark = [&, painted_cells, near_cells](const Point2& from, const Point2& to, double r) {
    const Point2 a = from;
    const Point2 b = to;
    const double paint2 = r2;
    ForEachCellNearSegmentIn(bounds, a, b, std::max(r, near_r), [&](int x, int y) {
      const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
      const size_t i = static_cast<size_t>(y - bounds.y0) * bounds.width + (x - bounds.x0);
      if (d2 <= paint2) painted_cells[i] = 1;
      if (d2 <= near2) near_cells[i] = 1;
    });
  };
  for (size_t k = 0; k < polylines.size(); ++k) {
    const double r = std::max(radii.empty() ? 0.0 : radii[k], min_radius);
    r2 = MarkedSquare(r);
    ForEachSegment(polylines[k], r, mark);
  }
}

}  // namespace fleetmap::vector_map
