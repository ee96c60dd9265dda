#include "common/vector_map/vector_map.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace fleetmap::vector_map {

size_t Polyline::SegmentCount() const {
  if (points.size() < 2) return 0;
  return closed && points.size() >= 3 ? points.size() : points.size() - 1;
}

size_t VectorMap::ObstacleVertexCount() const {
  size_t count = 0;
  for (const Polyline& polyline : obstacles) count += polyline.points.size();
  return count;
}

size_t VectorMap::ObstacleSegmentCount() const {
  size_t count = 0;
  for (const Polyline& polyline : obstacles) count += polyline.SegmentCount();
  return count;
}

size_t VectorMap::FreeVertexCount() const {
  size_t count = 0;
  for (const FreePolygon& polygon : free_space) {
    count += polygon.outer.size();
    for (const auto& hole : polygon.holes) count += hole.size();
  }
  return count;
}

void VectorMap::Append(const VectorMap& other) {
  obstacles.insert(obstacles.end(), other.obstacles.begin(), other.obstacles.end());
  free_space.insert(free_space.end(), other.free_space.begin(), other.free_space.end());
}

VectorMap Transformed(const VectorMap& map, const Transform2& to_from_map, std::string frame_id) {
  VectorMap out;
  out.frame_id = std::move(frame_id);
  out.resolution = map.resolution;
  out.epsilon = map.epsilon;
  const auto move_all = [&](std::vector<Point2> points) {
    for (Point2& point : points) point = to_from_map * point;
    return points;
  };
  out.obstacles.reserve(map.obstacles.size());
  for (const Polyline& polyline : map.obstacles) {
    out.obstacles.push_back(
        Polyline{move_all(polyline.points), polyline.closed, polyline.half_width});
  }
  out.free_space.reserve(map.free_space.size());
  for (const FreePolygon& polygon : map.free_space) {
    FreePolygon& moved = out.free_space.emplace_back();
    moved.outer = move_all(polygon.outer);
    for (const auto& hole : polygon.holes) moved.holes.push_back(move_all(hole));
  }
  return out;
}

std::optional<std::pair<Point2, Point2>> Bounds(const VectorMap& map) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Point2 low(kInf, kInf), high(-kInf, -kInf);
  const auto take = [&](const Point2& point, double grow) {
    low = low.cwiseMin(point - Point2(grow, grow));
    high = high.cwiseMax(point + Point2(grow, grow));
  };
  for (const Polyline& polyline : map.obstacles) {
    for (const Point2& point : polyline.points) take(point, polyline.half_width);
  }
  for (const FreePolygon& polygon : map.free_space) {
    for (const Point2& point : polygon.outer) take(point, 0.0);
  }
  if (!(low.x() <= high.x())) return std::nullopt;
  return std::make_pair(low, high);
}

double DefaultEpsilon(double resolution) { return std::numbers::sqrt2 * resolution; }

double HalfWidthStep(double epsilon) {
  return static_cast<double>(static_cast<float>(epsilon)) / kHalfWidthStepsPerEpsilon;
}

}  // namespace fleetmap::vector_map
