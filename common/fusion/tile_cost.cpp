#include "common/fusion/tile_cost.hpp"

#include <algorithm>
#include <cmath>

namespace fleetmap::fusion {
namespace {

double RingArea(const std::vector<Point2>& ring) {
  double twice = 0.0;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    twice += ring[j].x() * ring[i].y() - ring[i].x() * ring[j].y();
  }
  return std::abs(twice) / 2.0;
}

uint64_t Saturating(uint64_t a, uint64_t b) { return a > b ? a - b : 0; }

}  // namespace

TileCost& TileCost::operator+=(const TileCost& other) {
  vertices += other.vertices;
  rings += other.rings;
  cells += other.cells;
  bytes += other.bytes;
  return *this;
}

TileCost& TileCost::operator-=(const TileCost& other) {
  vertices = Saturating(vertices, other.vertices);
  rings = Saturating(rings, other.rings);
  cells = Saturating(cells, other.cells);
  bytes = Saturating(bytes, other.bytes);
  return *this;
}

uint64_t CellsPerTile(const fusion::FusionOptions& fusion) {
  const auto side = static_cast<uint64_t>(fusion.CellsPerTile());
  return side * side;
}

TileCost CostOfUnknownTile(const fusion::FusionOptions& fusion) {
  TileCost cost;
  cost.cells = CellsPerTile(fusion);
  cost.bytes = kBytesPerTile + kBytesPerContributedCell * cost.cells;
  return cost;
}

TileCost CostOf(const vector_map::VectorMap& map, const fusion::FusionOptions& fusion) {
  const double cell = fusion.FusedResolution();
  const double cell_area = cell * cell;
  TileCost cost;
  double painted = 0.0;  // square metres
  for (const vector_map::Polyline& polyline : map.obstacles) {
    cost.vertices += polyline.points.size();
    // A band of the half width (at least half a cell) around each segment, and its ends.
    const double radius = std::max(polyline.half_width, cell / 2.0);
    double length = 0.0;
    for (size_t i = 1; i < polyline.points.size(); ++i) {
      length += (polyline.points[i] - polyline.points[i - 1]).norm();
    }
    if (polyline.closed && polyline.points.size() >= 3) {
      length += (polyline.points.front() - polyline.points.back()).norm();
    }
    painted += (length + 2.0 * radius) * 2.0 * radius;
  }
  for (const vector_map::FreePolygon& polygon : map.free_space) {
    cost.rings += 1 + polygon.holes.size();
    cost.vertices += polygon.outer.size();
    if (!polygon.outer.empty()) painted += RingArea(polygon.outer);
    for (const auto& hole : polygon.holes) {
      cost.vertices += hole.size();
      if (!hole.empty()) painted += RingArea(hole);
    }
  }
  cost.cells = static_cast<uint64_t>(std::ceil(painted / cell_area));
  cost.bytes = kBytesPerTile + kBytesPerContributedCell * CellsPerTile(fusion) +
               kBytesPerVertex * cost.vertices + kBytesPerRing * cost.rings;
  return cost;
}

}  // namespace fleetmap::fusion
