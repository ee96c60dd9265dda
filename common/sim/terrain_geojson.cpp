#include "common/sim/terrain_geojson.hpp"

#include <string>

#include "common/gis/filled_area.hpp"
#include "common/gis/geojson_geometry.hpp"

namespace fleetmap::sim {
namespace {

using gis::GeoJsonPosition;

nlohmann::json Feature(nlohmann::json geometry, nlohmann::json properties) {
  return {{"type", "Feature"},
          {"geometry", std::move(geometry)},
          {"properties", std::move(properties)}};
}

}  // namespace

StatusOr<nlohmann::json> TerrainToGeoJson(const Terrain& terrain) {
  nlohmann::json features = nlohmann::json::array();
  for (const Wall& wall : terrain.walls) {
    features.push_back(
        Feature({{"type", "LineString"},
                 {"coordinates", {GeoJsonPosition(wall.a), GeoJsonPosition(wall.b)}}},
                {{"kind", std::string(ObstacleKindName(wall.kind))},
                 {"thickness", wall.thickness},
                 {"movable", wall.movable}}));
  }
  for (size_t i = 0; i < terrain.polygons.size(); ++i) {
    const SolidPolygon& polygon = terrain.polygons[i];
    StatusOr<gis::FilledArea> area = gis::FilledAreaOfRings({polygon.points});
    if (!area.ok()) {
      std::string message = "GeoJSON export of terrain polygon ";
      message.append(std::to_string(i)).append(": ").append(area.status().message());
      return InternalError(std::move(message));
    }
    for (nlohmann::json& geometry : gis::GeoJsonGeometries(*area)) {
      features.push_back(Feature(
          std::move(geometry),
          {{"kind", std::string(ObstacleKindName(polygon.kind))}, {"movable", polygon.movable}}));
    }
  }
  for (const Door& door : terrain.doors) {
    features.push_back(
        Feature({{"type", "LineString"},
                 {"coordinates", {GeoJsonPosition(door.a), GeoJsonPosition(door.b)}}},
                {{"kind", "door"}, {"open", door.open}, {"thickness", door.thickness}}));
  }
  return nlohmann::json{
      {"type", "FeatureCollection"},
      {"crs", gis::GeoJsonCrs()},
      {"properties",
       {{"terrain", std::string(TerrainKindName(terrain.kind))},
        {"size", terrain.size},
        {"seed", terrain.seed},
        {"frame", "map"},
        {"start", {{"x", terrain.start.x}, {"y", terrain.start.y}, {"yaw", terrain.start.yaw}}}}},
      {"features", std::move(features)}};
}

StatusOr<std::string> TerrainToGeoJsonString(const Terrain& terrain, int indent) {
  FLEETMAP_ASSIGN_OR_RETURN(const nlohmann::json json, TerrainToGeoJson(terrain));
  return json.dump(indent);
}

}  // namespace fleetmap::sim
