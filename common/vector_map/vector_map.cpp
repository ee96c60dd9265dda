#include "common/vector_map/vector_map.hpp"

#include <cmath>
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

double DefaultEpsilon(double resolution) { return std::numbers::sqrt2 * resolution; }

double HalfWidthStep(double epsilon) {
  return static_cast<double>(static_cast<float>(epsilon)) / kHalfWidthStepsPerEpsilon;
}

}  // namespace fleetmap::vector_map
