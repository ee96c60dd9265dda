#include "common/vector_map/geojson.hpp"

#include <vector>

#include "common/gis/filled_area.hpp"
#include "common/gis/geojson_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

using gis::GeoJsonPosition;

nlohmann::json ObstacleFeature(const Polyline& polyline) {
  nlohmann::json geometry;
  if (polyline.points.size() == 1) {
    // A zero-length LineString would be an invalid geometry to GEOS-based tools (QGIS, shapely).
    geometry = {{"type", "Point"}, {"coordinates", GeoJsonPosition(polyline.points.front())}};
  } else {
    nlohmann::json coordinates = nlohmann::json::array();
    for (const Point2& p : polyline.points) coordinates.push_back(GeoJsonPosition(p));
    if (polyline.closed) coordinates.push_back(GeoJsonPosition(polyline.points.front()));
    geometry = {{"type", "LineString"}, {"coordinates", coordinates}};
  }
  // The half width is what the rasterizer paints around the line: a reader needs it to draw
  // the obstacle as the grid will have it.
  return {{"type", "Feature"},
          {"properties",
           {{"kind", "obstacle"}, {"half_width", gis::GeoJsonMetres(polyline.half_width)}}},
          {"geometry", std::move(geometry)}};
}

}  // namespace

StatusOr<nlohmann::json> ToGeoJson(const VectorMap& map) {
  nlohmann::json features = nlohmann::json::array();
  for (const Polyline& polyline : map.obstacles) {
    if (!polyline.points.empty()) features.push_back(ObstacleFeature(polyline));
  }
  for (size_t i = 0; i < map.free_space.size(); ++i) {
    const FreePolygon& polygon = map.free_space[i];
    if (polygon.outer.empty()) continue;  // the rasterizer fills nothing for it either
    std::vector<std::vector<Point2>> rings = {polygon.outer};
    rings.insert(rings.end(), polygon.holes.begin(), polygon.holes.end());
    StatusOr<gis::FilledArea> area = gis::FilledAreaOfRings(rings);
    if (!area.ok()) {
      std::string message = "GeoJSON export of free polygon ";
      message.append(std::to_string(i)).append(": ").append(area.status().message());
      return InternalError(std::move(message));
    }
    for (nlohmann::json& geometry : gis::GeoJsonGeometries(*area)) {
      features.push_back({{"type", "Feature"},
                          {"properties", {{"kind", "free"}}},
                          {"geometry", std::move(geometry)}});
    }
  }
  return nlohmann::json{
      {"type", "FeatureCollection"},
      {"crs", gis::GeoJsonCrs()},
      {"properties",
       {{"epsilon", map.epsilon}, {"resolution", map.resolution}, {"frame", map.frame_id}}},
      {"features", std::move(features)}};
}

StatusOr<std::string> ToGeoJsonString(const VectorMap& map, int indent) {
  FLEETMAP_ASSIGN_OR_RETURN(const nlohmann::json json, ToGeoJson(map));
  return json.dump(indent);
}

}  // namespace fleetmap::vector_map
