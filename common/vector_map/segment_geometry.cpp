#include "common/vector_map/segment_geometry.hpp"

#include <utility>
#include <vector>

namespace fleetmap::vector_map {

bool IntervalsCover(std::vector<std::pair<double, double>>& intervals, double length) {
  // Intervals arrive nearly sorted (cells are visited along the major axis, which runs with or
  // against the segment): orient, then insertion sort, linear in practice.
  if (intervals.size() > 1 && intervals.front().first > intervals.back().first) {
    std::reverse(intervals.begin(), intervals.end());
  }
  for (size_t i = 1; i < intervals.size(); ++i) {
    const auto v = intervals[i];
    size_t j = i;
    while (j > 0 && intervals[j - 1].first > v.first) {
      intervals[j] = intervals[j - 1];
      --j;
    }
    intervals[j] = v;
  }
  double covered = 0.0;  // [0, covered] is inside the union so far
  for (const auto& [start, end] : intervals) {
    if (start > covered + kDistanceTolerance) return false;
    covered = std::max(covered, end);
    if (covered >= length) return true;
  }
  return covered >= length - kDistanceTolerance;
}

bool SegmentContinuous(const Point2& a, const Point2& b, double epsilon,
                       const Delimitation& delimitation) {
  return SegmentContinuousIf(a, b, epsilon,
                             [&](int x, int y) { return delimitation.IsDelimitation(x, y); });
}

double SampledMaxDistanceToDelimitation(const Point2& a, const Point2& b,
                                        const Delimitation& delimitation, double search_radius,
                                        double step) {
  const double length = (b - a).norm();
  const int samples = std::max(1, static_cast<int>(std::ceil(length / step)));
  double worst = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const Point2 q = a + (b - a) * (static_cast<double>(i) / samples);
    double best2 = search_radius * search_radius;
    ForEachCellNearSegment(q, q, search_radius, [&](int x, int y) {
      if (delimitation.IsDelimitation(x, y))
        best2 = std::min(best2, (Point2(x, y) - q).squaredNorm());
    });
    worst = std::max(worst, std::sqrt(best2));
  }
  return worst;
}

}  // namespace fleetmap::vector_map
