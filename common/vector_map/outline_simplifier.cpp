#include "common/vector_map/outline_simplifier.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "common/core/types.hpp"
#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

Point2 At(const std::vector<cv::Point>& contour, int k) {
  const cv::Point& p = contour[static_cast<size_t>(k) % contour.size()];
  return Point2(p.x, p.y);
}

// Whether the scan conversion of segment [a, b] may reach cell (x, y): within half a cell plus
// `slack` of it along its minor axis, inside its extent along the major axis. The Rasterizer's
// fillPoly and polylines both set, per row (column) the segment crosses, only cells within half a
// cell of the crossing.
bool InBand(int x, int y, const Point2& a, const Point2& b, double slack) {
  const double dx = b.x() - a.x();
  const double dy = b.y() - a.y();
  const double reach = 0.5 + slack;
  if (dx == 0.0 && dy == 0.0) return std::abs(x - a.x()) <= reach && std::abs(y - a.y()) <= reach;
  const bool along_x = std::abs(dx) >= std::abs(dy);
  const double u = along_x ? x : y;
  const double v = along_x ? y : x;
  const double au = along_x ? a.x() : a.y();
  const double av = along_x ? a.y() : a.x();
  const double du = along_x ? dx : dy;
  const double dv = along_x ? dy : dx;
  if (u < std::min(au, au + du) || u > std::max(au, au + du)) return false;
  return std::abs(v - (av + (u - au) * dv / du)) <= reach;
}

// Even-odd test of cell (x, y) against the polygon contour[i..j] closed back to contour[i]. Cells
// on its boundary are contour cells (never guarded) or lie in the segment's band.
bool InsideLens(int x, int y, const std::vector<cv::Point>& contour, int i, int j) {
  bool inside = false;
  for (int k = i; k <= j; ++k) {
    const Point2 p = At(contour, k);
    const Point2 q = At(contour, k < j ? k + 1 : i);
    if ((p.y() > y) != (q.y() > y)) {
      const double cross_x = p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y());
      if (x < cross_x) inside = !inside;
    }
  }
  return inside;
}

// Unrolled contour indices of the simplified vertices, in order (approxPolyDP keeps a subsequence
// of the contour, possibly starting elsewhere). A point the contour visits twice is matched at its
// first visit after the previous vertex: any such matching splits the contour into stretches
// joined end to end, which is all the lens argument needs. False if the vertices do not fit one
// turn of the contour.
bool MatchVertices(const std::vector<cv::Point>& contour, const std::vector<cv::Point>& simplified,
                   std::vector<int>* at) {
  const int n = static_cast<int>(contour.size());
  const auto first = std::find(contour.begin(), contour.end(), simplified.front());
  if (first == contour.end()) return false;
  const int start = static_cast<int>(first - contour.begin());
  at->assign(1, start);
  int pos = start;
  for (size_t m = 1; m < simplified.size(); ++m) {
    do {
      if (++pos >= start + n) return false;
    } while (contour[static_cast<size_t>(pos % n)] != simplified[m]);
    at->push_back(pos);
  }
  return true;
}

// Douglas-Peucker of a closed contour of integer points: what cv::approxPolyDP(contour, out,
// epsilon, true) gives (OpenCV 4.6), vertex for vertex and in the same order, without its
// InputArray, Mat and output copies (a tile has hundreds of contours, most of a few points, where
// those cost far more than the algorithm). Each step reproduces OpenCV's arithmetic, since ties and
// epsilon comparisons decide which points stay:
//  1. the start is found by three rounds of "the point farthest from the current start" (strictly
//     farther, first in contour order wins; the offset carries over to the next round); if every
//     point is within epsilon of the last start, that start alone is the result;
//  2. the ring is split there and at the farthest point, and each stretch is split at its point
//     farthest (strictly, first wins) from the chord's line, first half first, until within
//     epsilon; each stretch emits its first point;
//  3. a closing pass, in place and cyclic from the last vertex, drops a vertex within
//     epsilon / sqrt(2) of the line through its neighbours when their chord is neither horizontal
//     nor vertical and the vertex lies between them, then skips the vertex after it.
void ApproxClosed(const std::vector<cv::Point>& contour, double epsilon,
                  std::vector<cv::Point>& out) {
  out.clear();
  const int n = static_cast<int>(contour.size());
  if (n == 0) return;
  const double eps2 = epsilon * epsilon;
  // OpenCV computes the distances below in double from integer coordinates: the squares and cross
  // products are integers far below 2^53, so it computes them exactly, and the same integers give
  // the same comparisons. The cyclic scans run as two straight ones (no wrap test per point).
  const cv::Point* const c = contour.data();
  int start = 0;
  int offset = 0;
  int64_t farthest2 = 0;
  for (int round = 0; round < 3; ++round) {
    start = (start + offset) % n;
    const cv::Point s = c[start];
    farthest2 = 0;
    auto scan = [&](int from, int to, int first_offset) {
      for (int k = from; k < to; ++k) {
        const int64_t dx = c[k].x - s.x;
        const int64_t dy = c[k].y - s.y;
        const int64_t d2 = dx * dx + dy * dy;
        if (d2 > farthest2) {
          farthest2 = d2;
          offset = first_offset + (k - from);
        }
      }
    };
    scan(start + 1, n, 1);
    scan(0, start, n - start);
  }
  if (static_cast<double>(farthest2) <= eps2) {
    out.push_back(c[start]);
    return;
  }
  thread_local std::vector<std::pair<int, int>> stack;
  stack.clear();
  const int far = (start + offset) % n;
  stack.emplace_back(far, start);
  stack.emplace_back(start, far);
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    const cv::Point a = c[first];
    const int64_t dx = c[last].x - a.x;
    const int64_t dy = c[last].y - a.y;
    // (y - a.y) dx - (x - a.x) dy, with the terms of a taken out of the loop.
    const int64_t bias = a.y * dx - a.x * dy;
    int64_t worst = 0;
    int split = first;
    auto scan = [&](int from, int to) {
      for (int k = from; k < to; ++k) {
        const int64_t cross = c[k].y * dx - c[k].x * dy - bias;
        const int64_t d = cross < 0 ? -cross : cross;
        if (d > worst) {
          worst = d;
          split = k;
        }
      }
    };
    if (first < last) {
      scan(first + 1, last);
    } else {
      scan(first + 1, n);
      scan(0, last);
    }
    const double d = static_cast<double>(worst);
    const double ddx = static_cast<double>(dx);
    const double ddy = static_cast<double>(dy);
    if (d * d <= eps2 * (ddx * ddx + ddy * ddy)) {
      out.push_back(a);
    } else {
      stack.emplace_back(split, last);
      stack.emplace_back(first, split);
    }
  }
  // 3., on `out` as the ring buffer it works in (writes may wrap onto vertices not yet read).
  const int count = static_cast<int>(out.size());
  int kept = count;
  auto step = [count](int k) { return k + 1 < count ? k + 1 : 0; };
  int pos = count - 1;
  cv::Point prev = out[pos];
  pos = step(pos);
  int write = pos;
  cv::Point mid = out[pos];
  pos = step(pos);
  for (int i = 0; i < count && kept > 2; ++i) {
    const cv::Point end = out[pos];
    pos = step(pos);
    const double dx = end.x - prev.x;
    const double dy = end.y - prev.y;
    const double d = std::abs((mid.x - prev.x) * dy - (mid.y - prev.y) * dx);
    const int between = (mid.x - prev.x) * (end.x - mid.x) + (mid.y - prev.y) * (end.y - mid.y);
    if (d * d <= 0.5 * eps2 * (dx * dx + dy * dy) && dx != 0 && dy != 0 && between >= 0) {
      --kept;
      out[write] = prev = end;
      write = step(write);
      mid = out[pos];
      pos = step(pos);
      ++i;
      continue;
    }
    out[write] = prev = mid;
    write = step(write);
    mid = end;
  }
  out.resize(static_cast<size_t>(kept));
}

}  // namespace

OutlineSimplifier::OutlineSimplifier(const cv::Mat& guarded, double epsilon_cells)
    : guarded_(guarded),
      epsilon_(epsilon_cells),
      any_guarded_(!guarded.empty() && cv::countNonZero(guarded) > 0) {
  if (any_guarded_) cv::integral((guarded_ != 0) & 1, guarded_sum_, CV_32S);
}

bool OutlineSimplifier::AnyGuardedIn(int x0, int y0, int x1, int y1) const {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, guarded_.cols - 1);
  y1 = std::min(y1, guarded_.rows - 1);
  if (x0 > x1 || y0 > y1) return false;
  const int sum = guarded_sum_.at<int>(y1 + 1, x1 + 1) - guarded_sum_.at<int>(y0, x1 + 1) -
                  guarded_sum_.at<int>(y1 + 1, x0) + guarded_sum_.at<int>(y0, x0);
  return sum > 0;
}

bool OutlineSimplifier::AnyGuardedNear(const cv::Rect& box) const {
  if (!any_guarded_ || box.empty()) return false;
  return AnyGuardedIn(box.x - 1, box.y - 1, box.x + box.width, box.y + box.height);
}

bool OutlineSimplifier::SegmentSafe(const std::vector<cv::Point>& contour, int i, int j) const {
  if (j - i < 2) return true;  // one contour step: the lens is empty, the band region cells
  // The lens lies in the convex hull of its vertices and the band within a cell of the segment:
  // with no guarded cell in their bounding box (the usual case) there is nothing to visit.
  const size_t n = contour.size();
  int x0 = contour[static_cast<size_t>(i) % n].x;
  int y0 = contour[static_cast<size_t>(i) % n].y;
  int x1 = x0;
  int y1 = y0;
  for (int k = i + 1; k <= j; ++k) {
    const cv::Point& p = contour[static_cast<size_t>(k) % n];
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  if (!AnyGuardedIn(x0 - 1, y0 - 1, x1 + 1, y1 + 1)) return true;
  const Point2 a = At(contour, i);
  const Point2 b = At(contour, j);
  // The lens lies in the convex hull of its vertices, so within `reach` of the segment.
  double reach2 = 0.0;
  for (int k = i + 1; k < j; ++k) {
    reach2 = std::max(reach2, PointSegmentDistanceSquared(At(contour, k), a, b));
  }
  const double reach = std::max(std::sqrt(reach2), 0.5 + kSlack) + kSlack;
  bool safe = true;
  ForEachCellNearSegment(a, b, reach, [&](int x, int y) {
    if (!safe || !Guarded(x, y)) return;
    if (InBand(x, y, a, b, kSlack) || InsideLens(x, y, contour, i, j)) safe = false;
  });
  return safe;
}

void OutlineSimplifier::Refine(const std::vector<cv::Point>& contour, int i, int j,
                               std::vector<int>* kept) const {
  const size_t first = kept->size();
  const double epsilon2 = epsilon_ * epsilon_;
  thread_local std::vector<std::pair<int, int>> stack;
  stack.assign(1, {i, j});
  while (!stack.empty()) {
    const auto [lo, hi] = stack.back();
    stack.pop_back();
    if (hi - lo < 2) continue;
    const Point2 a = At(contour, lo);
    const Point2 b = At(contour, hi);
    int farthest = lo + 1;
    double farthest2 = -1.0;
    for (int k = lo + 1; k < hi; ++k) {
      const double d2 = PointSegmentDistanceSquared(At(contour, k), a, b);
      if (d2 > farthest2) {
        farthest2 = d2;
        farthest = k;
      }
    }
    if (farthest2 <= epsilon2 && SegmentSafe(contour, lo, hi)) continue;
    kept->push_back(farthest);
    stack.emplace_back(lo, farthest);
    stack.emplace_back(farthest, hi);
  }
  std::sort(kept->begin() + static_cast<std::ptrdiff_t>(first), kept->end());
}

void OutlineSimplifier::Simplify(const std::vector<cv::Point>& contour,
                                 std::vector<cv::Point>* ring) const {
  ApproxClosed(contour, epsilon_, *ring);
  if (!any_guarded_ || contour.size() < 3 || ring->empty()) return;
  const int n = static_cast<int>(contour.size());
  thread_local std::vector<int> kept;
  thread_local std::vector<int> at;
  kept.clear();
  if (MatchVertices(contour, *ring, &at)) {
    bool changed = false;
    for (size_t m = 0; m < at.size(); ++m) {
      const int i = at[m];
      const int j = m + 1 < at.size() ? at[m + 1] : at[0] + n;
      kept.push_back(i);
      if (!SegmentSafe(contour, i, j)) {
        Refine(contour, i, j, &kept);
        changed = true;
      }
    }
    if (!changed) return;
  } else {
    // The whole ring, checked: split at its first point and the point farthest from it.
    int farthest = 0;
    double farthest2 = 0.0;
    for (int k = 1; k < n; ++k) {
      const double d2 = (At(contour, k) - At(contour, 0)).squaredNorm();
      if (d2 > farthest2) {
        farthest2 = d2;
        farthest = k;
      }
    }
    kept.push_back(0);
    if (farthest > 0) {
      Refine(contour, 0, farthest, &kept);
      kept.push_back(farthest);
      Refine(contour, farthest, n, &kept);
    }
  }
  ring->clear();
  for (const int k : kept) ring->push_back(contour[static_cast<size_t>(k % n)]);
}

}  // namespace fleetmap::vector_map
