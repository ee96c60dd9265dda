#include "common/vector_map/cell_polyline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

namespace fleetmap::vector_map {

CellPolyline MakePolyline(const std::vector<Point2>& points, const std::vector<int>& piece) {
  CellPolyline polyline;
  polyline.points.reserve(piece.size());
  for (const int index : piece) polyline.points.push_back(points[index]);
  if (polyline.points.size() >= 2 && polyline.points.front() == polyline.points.back()) {
    polyline.points.pop_back();
    polyline.closed = polyline.points.size() >= 3;
  }
  return polyline;
}

bool IsHairpin(const Point2& from, const Point2& at, const Point2& to) {
  const Point2 in = at - from;
  const Point2 out = to - at;
  return in.dot(out) < -0.5 * in.norm() * out.norm();
}

std::vector<CellPolyline> SplitAtHairpins(const std::vector<CellPolyline>& polylines) {
  std::vector<CellPolyline> split;
  for (const CellPolyline& polyline : polylines) {
    const auto& pts = polyline.points;
    if (polyline.closed || pts.size() < 3) {
      split.push_back(polyline);
      continue;
    }
    CellPolyline piece;
    piece.start_on_border = polyline.start_on_border;
    for (size_t k = 0; k < pts.size(); ++k) {
      piece.points.push_back(pts[k]);
      if (k > 0 && k + 1 < pts.size() && IsHairpin(pts[k - 1], pts[k], pts[k + 1])) {
        split.push_back(piece);
        piece = CellPolyline{};
        piece.points.push_back(pts[k]);
      }
    }
    piece.end_on_border = polyline.end_on_border;
    split.push_back(std::move(piece));
  }
  return split;
}

std::vector<CellPolyline> MergeAtSharedEnds(std::vector<CellPolyline> polylines) {
  const int n = static_cast<int>(polylines.size());
  auto mergeable = [&](int i) { return !polylines[i].closed && polylines[i].points.size() >= 2; };
  // (end point, end id): ends sorted by point, then paired in input order within a point.
  std::vector<std::tuple<int64_t, int64_t, int>> ends;
  for (int i = 0; i < n; ++i) {
    if (!mergeable(i)) continue;
    for (int side = 0; side < 2; ++side) {
      const bool on_border = side == 0 ? polylines[i].start_on_border : polylines[i].end_on_border;
      if (on_border) continue;
      const Point2& p = side == 0 ? polylines[i].points.front() : polylines[i].points.back();
      // Vertices are cell centres or half-cell border nodes; 1/1024 cell keys tell them apart.
      ends.emplace_back(std::llround(p.x() * 1024.0), std::llround(p.y() * 1024.0), 2 * i + side);
    }
  }
  std::sort(ends.begin(), ends.end());
  // The vertex next to end e, inside its polyline.
  auto inner = [&](int e) -> const Point2& {
    const auto& pts = polylines[e / 2].points;
    return e % 2 == 0 ? pts[1] : pts[pts.size() - 2];
  };
  std::vector<int> partner(2 * static_cast<size_t>(n), -1);
  for (size_t k = 0; k + 1 < ends.size();) {
    const auto& [x0, y0, e0] = ends[k];
    const auto& [x1, y1, e1] = ends[k + 1];
    const bool same =
        x0 == x1 && y0 == y1 &&
        polylines[e0 / 2].points[e0 % 2 == 0 ? 0 : polylines[e0 / 2].points.size() - 1] ==
            polylines[e1 / 2].points[e1 % 2 == 0 ? 0 : polylines[e1 / 2].points.size() - 1];
    const Point2& at =
        polylines[e0 / 2].points[e0 % 2 == 0 ? 0 : polylines[e0 / 2].points.size() - 1];
    if (same && e0 / 2 != e1 / 2 && !IsHairpin(inner(e0), at, inner(e1))) {
      partner[e0] = e1;
      partner[e1] = e0;
      k += 2;
    } else {
      ++k;
    }
  }
  std::vector<CellPolyline> merged;
  merged.reserve(polylines.size());
  std::vector<bool> used(n, false);
  auto walk = [&](int start_end, bool cycle) {
    CellPolyline out;
    int end = start_end;
    out.start_on_border =
        (end % 2 == 0) ? polylines[end / 2].start_on_border : polylines[end / 2].end_on_border;
    while (true) {
      const int i = end / 2;
      used[i] = true;
      const auto& pts = polylines[i].points;
      const bool forward = end % 2 == 0;
      const size_t skip = out.points.empty() ? 0 : 1;
      for (size_t k = skip; k < pts.size(); ++k) {
        out.points.push_back(forward ? pts[k] : pts[pts.size() - 1 - k]);
      }
      const int exit_end = forward ? 2 * i + 1 : 2 * i;
      out.end_on_border = forward ? polylines[i].end_on_border : polylines[i].start_on_border;
      const int next = partner[exit_end];
      if (next < 0 || used[next / 2]) break;
      end = next;
    }
    if (cycle && out.points.size() >= 2 && out.points.front() == out.points.back()) {
      out.points.pop_back();
      out.closed = out.points.size() >= 3;
    }
    merged.push_back(std::move(out));
  };
  for (int i = 0; i < n; ++i) {
    if (used[i]) continue;
    if (!mergeable(i)) {
      used[i] = true;
      merged.push_back(std::move(polylines[i]));
      continue;
    }
    if (partner[2 * i] < 0) {
      walk(2 * i, false);
    } else if (partner[2 * i + 1] < 0) {
      walk(2 * i + 1, false);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) walk(2 * i, true);  // what is left are cycles
  }
  return merged;
}

}  // namespace fleetmap::vector_map
