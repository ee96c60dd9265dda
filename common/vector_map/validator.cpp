#include "common/vector_map/validator.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

StatusOr<ValidationReport> Validator::Validate(const VectorMap& map,
                                               const grid::OccupancyGrid& source) const {
  const double resolution = source.resolution();
  if (!(resolution > 0.0)) return InvalidArgumentError("validate: grid resolution must be > 0");
  const double epsilon = options_.epsilon > 0.0 ? options_.epsilon : map.epsilon;
  if (!(epsilon > 0.0)) return InvalidArgumentError("validate: epsilon must be > 0");
  const CellRect rect = options_.rect.value_or(FullRect(source));
  const double eps = epsilon / resolution;
  const double eps2 = ToleratedSquare(eps);
  const double search = 2.0 * eps + 2.0;
  const CellFrame frame(source);
  const Delimitation delimitation(source, rect, static_cast<int>(std::ceil(search)) + 2,
                                  options_.thresholds);

  // Every edge in cell coordinates; a point obstacle is a zero-length edge.
  std::vector<std::pair<Point2, Point2>> segments;
  for (const Polyline& polyline : map.obstacles) {
    std::vector<Point2> pts;
    pts.reserve(polyline.points.size());
    for (const Point2& p : polyline.points) pts.push_back(frame.ToCell(p));
    if (pts.size() == 1) segments.emplace_back(pts[0], pts[0]);
    for (size_t k = 0; k + 1 < pts.size(); ++k) segments.emplace_back(pts[k], pts[k + 1]);
    if (polyline.closed && pts.size() >= 3) segments.emplace_back(pts.back(), pts.front());
  }

  ValidationReport report;
  report.segments = static_cast<int64_t>(segments.size());
  const double search2 = search * search;
  std::vector<double> nearest(static_cast<size_t>(rect.cell_count()), search2);
  for (const auto& [a, b] : segments) {
    // Captured by name: clang before 16 cannot capture a structured binding (C++20 allows it).
    ForEachCellNearSegment(a, b, search, [&, &a = a, &b = b](int x, int y) {
      if (!rect.Contains(x, y)) return;
      double& best = nearest[static_cast<size_t>(y - rect.y0) * rect.width + (x - rect.x0)];
      best = std::min(best, PointSegmentDistanceSquared(Point2(x, y), a, b));
    });
    if (!SegmentContinuous(a, b, eps, delimitation)) ++report.discontinuous_segments;
    if (options_.measure_segment_distance) {
      report.worst_segment_distance =
          std::max(report.worst_segment_distance,
                   SampledMaxDistanceToDelimitation(a, b, delimitation, search, 0.1) * resolution);
    }
  }
  double worst2 = 0.0;
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    for (int x = rect.x0; x < rect.x0 + rect.width; ++x) {
      if (!delimitation.IsDelimitation(x, y)) continue;
      ++report.delimitation_points;
      const double best = nearest[static_cast<size_t>(y - rect.y0) * rect.width + (x - rect.x0)];
      worst2 = std::max(worst2, best);
      if (best > eps2) ++report.uncovered_points;
    }
  }
  report.worst_point_distance = std::sqrt(worst2) * resolution;
  return report;
}

}  // namespace fleetmap::vector_map
