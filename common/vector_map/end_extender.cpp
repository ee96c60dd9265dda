#include "common/vector_map/end_extender.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

// The painting test of PaintedCells (a relative 1e-10 above the radius).
double PaintSquare(double radius) { return radius * radius * (1.0 + 1e-10); }

// A zeroed per-thread flag image, reused across calls (the run restores the zeros), so large
// grids do not pay for allocating and clearing a full image on every call.
std::vector<uint8_t>& ZeroedFlags(size_t size) {
  thread_local std::vector<uint8_t> flags;
  if (flags.size() < size) flags.resize(size, 0);
  return flags;
}

class EndRun {
 public:
  EndRun(const CellRaster& raster, const std::vector<double>& radii,
         const EndExtensionOptions& options, std::vector<CellPolyline>& polylines)
      : raster_(raster),
        radii_(radii),
        options_(options),
        polylines_(polylines),
        eps2_(ToleratedSquare(options.epsilon)),
        painted_(ZeroedFlags(raster.size())) {}
  ~EndRun() {
    for (const int i : painted_cells_) painted_[i] = 0;
  }
  EndRun(const EndRun&) = delete;
  EndRun& operator=(const EndRun&) = delete;

  int Run() {
    for (size_t k = 0; k < polylines_.size(); ++k) {
      const CellPolyline& polyline = polylines_[k];
      const auto& pts = polyline.points;
      const double r2 = PaintSquare(Radius(k));
      auto mark = [&](const Point2& a, const Point2& b) { Paint(a, b, Radius(k), r2); };
      if (pts.size() == 1) mark(pts[0], pts[0]);
      for (size_t i = 0; i + 1 < pts.size(); ++i) mark(pts[i], pts[i + 1]);
      if (polyline.closed && pts.size() >= 3) mark(pts.back(), pts.front());
    }
    int extended = 0;
    for (size_t k = 0; k < polylines_.size(); ++k) {
      CellPolyline& polyline = polylines_[k];
      if (polyline.closed || polyline.points.size() < 2) continue;
      if (!polyline.start_on_border && TryEnd(k, 0)) ++extended;
      if (!polyline.end_on_border && TryEnd(k, 1)) ++extended;
    }
    return extended;
  }

 private:
  double Radius(size_t k) const {
    return std::max(radii_.empty() ? 0.0 : radii_[k], options_.min_radius);
  }
  bool Painted(int x, int y) const {
    return raster_.Contains(x, y) && painted_[raster_.Index(x, y)] != 0;
  }
  bool Occupied(int x, int y) const {
    return raster_.Contains(x, y) && raster_.Has(raster_.Index(x, y), CellRaster::kOccupied);
  }
  bool InTile(int x, int y) const {
    const CellRect& rect = raster_.rect();
    return x >= rect.x0 && y >= rect.y0 && x < rect.x0 + rect.width && y < rect.y0 + rect.height;
  }
  void Paint(const Point2& a, const Point2& b, double r, double r2) {
    ForEachCellNearSegmentIn(raster_.window(), a, b, r, [&](int x, int y) {
      if (PointSegmentDistanceSquared(Point2(x, y), a, b) <= r2) {
        uint8_t& painted = painted_[raster_.Index(x, y)];
        if (painted == 0) {
          painted = 1;
          painted_cells_.push_back(raster_.Index(x, y));
        }
      }
    });
  }
  Point2 Snap(const Point2& p) const { return options_.snap ? options_.snap(p) : p; }

  // Tries to move end `side` of polyline k outward along its last segment.
  bool TryEnd(size_t k, int side) {
    auto& pts = polylines_[k].points;
    const size_t end_index = side == 0 ? 0 : pts.size() - 1;
    const Point2 end = pts[end_index];
    const Point2 inner = pts[side == 0 ? 1 : pts.size() - 2];
    const Point2 axis = end - inner;
    const double length = axis.norm();
    if (length <= kDistanceTolerance) return false;
    const Point2 dir = axis / length;
    const double r = Radius(k);
    const double r2 = PaintSquare(r);
    // Unpainted occupied cells of the tile ahead of the end: its new position is one of their
    // centres (the coordinates other vertices use, so the wire bytes compress as well as
    // before), farthest along first, so that one move paints as many of them as it can.
    candidates_.clear();
    const double reach = 2.0 * options_.epsilon;
    // Cells of the tile only (the raster holds the tile, so no bounds check per cell).
    const CellRect& rect = raster_.rect();
    const int x_lo = std::max(static_cast<int>(std::floor(end.x() - reach)), rect.x0);
    const int x_hi =
        std::min(static_cast<int>(std::ceil(end.x() + reach)), rect.x0 + rect.width - 1);
    const int y_lo = std::max(static_cast<int>(std::floor(end.y() - reach)), rect.y0);
    const int y_hi =
        std::min(static_cast<int>(std::ceil(end.y() + reach)), rect.y0 + rect.height - 1);
    for (int y = y_lo; y <= y_hi; ++y) {
      for (int x = x_lo; x <= x_hi; ++x) {
        const int i = raster_.Index(x, y);
        if (!raster_.Has(i, CellRaster::kOccupied) || painted_[i] != 0) continue;
        const Point2 w = Point2(x, y) - end;
        const double along = w.dot(dir);
        if (along <= 0.0 || w.squaredNorm() > reach * reach) continue;
        candidates_.emplace_back(-along, Point2(x, y));
      }
    }
    if (candidates_.empty()) return false;
    std::sort(candidates_.begin(), candidates_.end(), [](const auto& a, const auto& b) {
      return std::tie(a.first, a.second.y(), a.second.x()) <
             std::tie(b.first, b.second.y(), b.second.x());
    });
    for (const auto& [key, cell] : candidates_) {
      const Point2 moved = Snap(cell);
      if (Accept(inner, end, moved, r, r2)) {
        pts[end_index] = moved;
        Paint(inner, moved, r, r2);
        return true;
      }
    }
    return false;
  }

  // The checks (a)-(d) of the header for segment [inner, end] becoming [inner, moved].
  bool Accept(const Point2& inner, const Point2& end, const Point2& moved, double r, double r2) {
    // (b) P points near the old segment stay within epsilon; (c) its painted cells stay painted.
    bool ok = true;
    const CellRect window = raster_.window();
    // A cell beyond both radii of the old segment constrains nothing (no second distance).
    const double bound2 = std::max(r2, eps2_);
    ForEachCellNearSegmentIn(window, inner, end, std::max(options_.epsilon, r), [&](int x, int y) {
      if (!ok) return;
      const Point2 c(x, y);
      const double before = PointSegmentDistanceSquared(c, inner, end);
      if (before > bound2) return;
      const double after = PointSegmentDistanceSquared(c, inner, moved);
      if (before <= r2 && after > r2) ok = false;
      if (before <= eps2_ && after > eps2_ && raster_.IsDelimitation(x, y)) ok = false;
    });
    if (!ok) return false;
    // (d) newly painted cells: occupied ones of the tile against cells that are not occupied.
    int gain = 0;
    int loss = 0;
    ForEachCellNearSegmentIn(window, inner, moved, r, [&](int x, int y) {
      if (Painted(x, y)) return;
      if (PointSegmentDistanceSquared(Point2(x, y), inner, moved) > r2) return;
      if (!Occupied(x, y)) {
        ++loss;
      } else if (InTile(x, y)) {
        ++gain;
      }
    });
    if (gain <= loss) return false;
    // (a) the lengthened segment is continuous (exact).
    return SegmentContinuousIf(inner, moved, options_.epsilon,
                               [&](int x, int y) { return raster_.IsDelimitation(x, y); });
  }

  const CellRaster& raster_;
  const std::vector<double>& radii_;
  const EndExtensionOptions& options_;
  std::vector<CellPolyline>& polylines_;
  double eps2_;
  std::vector<uint8_t>& painted_;  // per thread, zero outside painted_cells_
  std::vector<int> painted_cells_;
  std::vector<std::pair<double, Point2>> candidates_;  // (-along, cell)
};

}  // namespace

int ExtendLineEnds(const CellRaster& raster, const std::vector<double>& radii,
                   const EndExtensionOptions& options, std::vector<CellPolyline>& polylines) {
  return EndRun(raster, radii, options, polylines).Run();
}

}  // namespace fleetmap::vector_map
