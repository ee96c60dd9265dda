#include "common/vector_map/geojson.hpp"

#include <vector>

namespace fleetmap::vector_map {
namespace {

nlohmann::json Position(const Point2& p) { return nlohmann::json::array({p.x(), p.y()}); }

// A closed linear ring: at least four positions, first == last.
nlohmann::json Ring(const std::vector<Point2>& ring) {
  nlohmann::json out = nlohmann::json::array();
  for (const Point2& p : ring) out.push_back(Position(p));
  if (!ring.empty()) {
    out.push_back(Position(ring.front()));
    while (out.size() < 4) out.push_back(Position(ring.front()));
  }
  return out;
}

}  // namespace

nlohmann::json ToGeoJson(const VectorMap& map) {
  nlohmann::json features = nlohmann::json::array();
  for (const Polyline& polyline : map.obstacles) {
    if (polyline.points.empty()) continue;
    nlohmann::json geometry;
    if (polyline.points.size() == 1) {
      // A zero-length LineString would be an invalid geometry to GEOS-based tools (QGIS, shapely).
      geometry = {{"type", "Point"}, {"coordinates", Position(polyline.points.front())}};
    } else {
      nlohmann::json coordinates = nlohmann::json::array();
      for (const Point2& p : polyline.points) coordinates.push_back(Position(p));
      if (polyline.closed) coordinates.push_back(Position(polyline.points.front()));
      geometry = {{"type", "LineString"}, {"coordinates", coordinates}};
    }
    // The half width is what the rasterizer paints around the line: a reader needs it to draw
    // the obstacle as the grid will have it.
    features.push_back({{"type", "Feature"},
                        {"properties", {{"kind", "obstacle"}, {"half_width", polyline.half_width}}},
                        {"geometry", geometry}});
  }
  for (const FreePolygon& polygon : map.free_space) {
    if (polygon.outer.empty()) continue;
    nlohmann::json rings = nlohmann::json::array();
    rings.push_back(Ring(polygon.outer));
    for (const auto& hole : polygon.holes) {
      if (!hole.empty()) rings.push_back(Ring(hole));
    }
    features.push_back({{"type", "Feature"},
                        {"properties", {{"kind", "free"}}},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", rings}}}});
  }
  return {{"type", "FeatureCollection"},
          {"properties",
           {{"epsilon", map.epsilon}, {"resolution", map.resolution}, {"frame", map.frame_id}}},
          {"features", features}};
}

std::string ToGeoJsonString(const VectorMap& map, int indent) {
  return ToGeoJson(map).dump(indent);
}

}  // namespace fleetmap::vector_map
