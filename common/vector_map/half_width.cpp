#include "common/vector_map/half_width.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
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
  thread_local std::vector<int> touched;
  touched.clear();
  // The cell loop reads only locals: the stores into best and owner may alias what is read
  // through a reference, which would then be reloaded for every cell.
  const CellRect bounds = rect;
  const CellRect window = raster.window();
  float* const best_d2 = best.data();
  int* const owners = owner.data();
  auto visit = [&, best_d2, owners](int polyline, const Point2& from, const Point2& to) {
    const Point2 a = from;
    const Point2 b = to;
    ForEachCellNearSegmentIn(bounds, a, b, epsilon, [&](int x, int y) {
      const int i = (y - window.y0) * window.width + (x - window.x0);  // raster.Index(x, y)
      const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
      if (d2 > eps2) return;
      if (best_d2[i] < 0.0f) {
        touched.push_back(i);
      } else if (static_cast<double>(best_d2[i]) <= d2) {
        return;
      }
      best_d2[i] = static_cast<float>(d2);
      owners[i] = polyline;
    });
  };
  for (size_t p = 0; p < polylines.size(); ++p) {
    const auto& pts = polylines[p].points;
    const int id = static_cast<int>(p);
    if (pts.size() == 1) visit(id, pts[0], pts[0]);
    for (size_t k = 0; k + 1 < pts.size(); ++k) visit(id, pts[k], pts[k + 1]);
    if (polylines[p].closed && pts.size() >= 3) visit(id, pts.back(), pts.front());
  }
  // Cells beyond the minimum radius, grouped by polyline (counting sort), each as the key
  // (float bits of d2) << 1 | occupied: d2 >= 0, so its bits order like the value, and sorting the
  // keys of one polyline orders its cells by distance (ties side by side).
  const double min2 = ToleratedSquare(min_half_width);
  thread_local std::vector<int> start;
  thread_local std::vector<uint32_t> keys;
  start.assign(polylines.size() + 1, 0);
  size_t count = 0;
  for (const int i : touched) {
    if (static_cast<double>(best[i]) > min2) {
      ++start[owner[i] + 1];
      ++count;
    }
  }
  for (size_t p = 1; p < start.size(); ++p) start[p] += start[p - 1];
  keys.resize(count);
  for (const int i : touched) {
    if (static_cast<double>(best[i]) > min2) {
      const uint32_t bits = std::bit_cast<uint32_t>(best[i]);
      keys[start[owner[i]]++] = bits << 1 | (raster.Has(i, CellRaster::kOccupied) ? 1u : 0u);
    }
    best[i] = -1.0f;
  }
  // start[p] now ends polyline p's keys.
  std::vector<double> half_widths(polylines.size(), 0.0);
  int begin = 0;
  for (size_t p = 0; p < polylines.size(); ++p) {
    const int end = start[p];
    if (end == begin) continue;
    std::sort(keys.begin() + begin, keys.begin() + end);
    int sum = 0;
    int best_sum = 0;
    uint32_t best_bits = 0;
    for (int k = begin; k < end; ++k) {
      sum += (keys[k] & 1u) ? 1 : -1;
      // Ties at one distance are decided together (a radius takes all of them or none).
      const bool last_at_distance = k + 1 == end || (keys[k + 1] >> 1) != (keys[k] >> 1);
      if (last_at_distance && sum > best_sum) {
        best_sum = sum;
        best_bits = keys[k] >> 1;
      }
    }
    const double best_d2 = static_cast<double>(std::bit_cast<float>(best_bits));
    // Rounded up by a float ulp or so: the radius must not fall short of the cells it chose.
    half_widths[p] = std::min(epsilon, std::sqrt(best_d2) * (1.0 + 1e-6));
    begin = end;
  }
  return half_widths;
}

int PaintMatch(CellRaster& raster, const std::vector<CellPolyline>& polylines, double epsilon,
               double min_half_width) {
  const std::vector<double> half_widths =
      CoveredHalfWidths(raster, polylines, epsilon, min_half_width);
  thread_local std::vector<int> painted;
  painted.clear();
  int match = 0;
  auto paint = [&](const Point2& a, const Point2& b, double radius) {
    const double r2 = ToleratedSquare(radius);
    ForEachCellNearSegmentIn(raster.rect(), a, b, radius, [&](int x, int y) {
      const int i = raster.Index(x, y);
      if (raster.Has(i, CellRaster::kVisited) ||
          PointSegmentDistanceSquared(Point2(x, y), a, b) > r2) {
        return;
      }
      raster.at(i) |= CellRaster::kVisited;
      painted.push_back(i);
      match += raster.Has(i, CellRaster::kOccupied) ? 1 : -1;
    });
  };
  for (size_t p = 0; p < polylines.size(); ++p) {
    const auto& pts = polylines[p].points;
    const double radius = std::max(half_widths[p], min_half_width);
    if (pts.size() == 1) paint(pts[0], pts[0], radius);
    for (size_t k = 0; k + 1 < pts.size(); ++k) paint(pts[k], pts[k + 1], radius);
    if (polylines[p].closed && pts.size() >= 3) paint(pts.back(), pts.front(), radius);
  }
  raster.Clear(painted, CellRaster::kVisited);
  return match;
}

}  // namespace fleetmap::vector_map
