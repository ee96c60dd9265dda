#include "common/vector_map/speck_cover.hpp"

#include <cmath>
#include <utility>

#include "common/vector_map/chain_simplifier.hpp"
#include "common/vector_map/segment_geometry.hpp"
#include "common/vector_map/skeleton.hpp"

namespace fleetmap::vector_map {

void MarkCovered(CellRaster& raster, const Point2& from, const Point2& to, double epsilon) {
  const double eps2 = ToleratedSquare(epsilon);
  // The cell loop reads only locals: a byte store may alias anything read through a reference or
  // the raster's members, which would then be reloaded for every cell.
  const Point2 a = from;
  const Point2 b = to;
  const CellRect window = raster.window();
  uint8_t* const flags = &raster.at(0);
  ForEachCellNearSegmentIn(window, a, b, epsilon, [&, flags](int x, int y) {
    const int i = (y - window.y0) * window.width + (x - window.x0);  // raster.Index(x, y)
    if ((flags[i] & (CellRaster::kOwned | CellRaster::kCovered)) != CellRaster::kOwned) return;
    if (PointSegmentDistanceSquared(Point2(x, y), a, b) <= eps2) flags[i] |= CellRaster::kCovered;
  });
}

void MarkCovered(CellRaster& raster, const CellPolyline& polyline, double epsilon) {
  const auto& pts = polyline.points;
  if (pts.size() == 1) MarkCovered(raster, pts[0], pts[0], epsilon);
  for (size_t k = 0; k + 1 < pts.size(); ++k) MarkCovered(raster, pts[k], pts[k + 1], epsilon);
  if (polyline.closed) MarkCovered(raster, pts.back(), pts.front(), epsilon);
}

namespace {

// Chains the points `open` accepts, starting from each of `starts` in turn, through neighbours up
// to 2 epsilon apart (nearest first), calling `take` on each point chained, and appends each
// chain simplified with the full check.
template <typename Open, typename Take>
void CoverChains(const CellRaster& raster, double epsilon, const std::vector<int>& starts,
                 Open open, Take take, std::vector<CellPolyline>& polylines) {
  const double eps2 = ToleratedSquare(epsilon);
  auto is_p = [&](int x, int y) { return raster.IsDelimitation(x, y); };
  // Per-thread storage (a tile runs this for about a hundred chains): the neighbour offsets are
  // rebuilt only when the raster's stride or epsilon changes, and the buffers keep their capacity.
  thread_local std::vector<int> links;
  thread_local int links_stride = 0;
  thread_local double links_epsilon = -1.0;
  if (links_stride != raster.stride() || links_epsilon != epsilon) {
    links = DiscOffsets(raster, 2.0 * epsilon);
    links.erase(links.begin());  // the cell itself
    links_stride = raster.stride();
    links_epsilon = epsilon;
  }
  thread_local std::vector<int> forward;
  thread_local std::vector<int> backward;
  thread_local std::vector<Point2> chain;
  thread_local std::vector<std::vector<int>> pieces;
  thread_local std::vector<std::pair<double, double>> intervals;
  for (const int start : starts) {
    if (!open(start)) continue;
    take(start);
    forward.assign(1, start);
    backward.clear();
    for (auto* walk : {&forward, &backward}) {
      int current = start;
      while (true) {
        int next = -1;
        for (const int o : links) {
          if (open(current + o)) {
            next = current + o;
            break;
          }
        }
        if (next < 0) break;
        take(next);
        walk->push_back(next);
        current = next;
      }
    }
    chain.clear();
    for (auto it = backward.rbegin(); it != backward.rend(); ++it) {
      chain.emplace_back(raster.X(*it), raster.Y(*it));
    }
    for (const int i : forward) chain.emplace_back(raster.X(i), raster.Y(i));
    auto valid = [&](int i, int j) {
      const Point2& a = chain[i];
      const Point2& b = chain[j];
      for (int k = i + 1; k < j; ++k) {
        if (PointSegmentDistanceSquared(chain[k], a, b) > eps2) return false;
      }
      // The chain's own points are P points: if their epsilon-disc intervals already cover the
      // segment it is continuous (sound); else the exact test against all of P decides.
      const double length = (b - a).norm();
      if (length > kDistanceTolerance) {
        const Point2 u = (b - a) / length;
        intervals.clear();
        for (int k = i; k <= j; ++k) {
          const Point2 w = chain[k] - a;
          const double along = w.dot(u);
          const double half2 = eps2 - (w.squaredNorm() - along * along);
          if (half2 < 0.0) continue;
          const double half = std::sqrt(half2);
          intervals.emplace_back(along - half, along + half);
        }
        if (IntervalsCover(intervals, length)) return true;
      }
      return SegmentContinuousIf(a, b, epsilon, is_p);
    };
    pieces.clear();
    SimplifyChain(static_cast<int>(chain.size()), valid, pieces);
    for (const auto& piece : pieces) polylines.push_back(MakePolyline(chain, piece));
  }
}

}  // namespace

void CoverRemaining(CellRaster& raster, double epsilon, std::vector<CellPolyline>& polylines) {
  for (const CellPolyline& polyline : polylines) MarkCovered(raster, polyline, epsilon);
  CoverChains(
      raster, epsilon, raster.owned_delimitation(),
      [&](int i) {
        return (raster.at(i) & (CellRaster::kOwned | CellRaster::kCovered)) == CellRaster::kOwned;
      },
      [&](int i) { raster.at(i) |= CellRaster::kCovered; }, polylines);
}

void CoverPoints(CellRaster& raster, double epsilon, const std::vector<int>& points,
                 std::vector<CellPolyline>& polylines) {
  for (const int i : points) raster.at(i) |= CellRaster::kVisited;
  CoverChains(
      raster, epsilon, points, [&](int i) { return raster.Has(i, CellRaster::kVisited); },
      [&](int i) { raster.at(i) &= static_cast<uint8_t>(~CellRaster::kVisited); }, polylines);
}

}  // namespace fleetmap::vector_map
