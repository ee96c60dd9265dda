#include "common/sim/terrain_geojson.hpp"

#include <string>

namespace fleetmap::sim {
namespace {

nlohmann::json Position(const Point2& p) { return nlohmann::json::array({p.x(), p.y()}); }

nlohmann::json Feature(nlohmann::json geometry, nlohmann::json properties) {
  return {{"type", "Feature"},
          {"geometry", std::move(geometry)},
          {"properties", std::move(properties)}};
}

}  // namespace

nlohmann::json TerrainToGeoJson(const Terrain& terrain) {
  nlohmann::json features = nlohmann::json::array();
  for (const Wall& wall : terrain.walls) {
    features.push_back(
        Feature({{"type", "LineString"}, {"coordinates", {Position(wall.a), Position(wall.b)}}},
                {{"kind", std::string(ObstacleKindName(wall.kind))},
                 {"thickness", wall.thickness},
                 {"movable", wall.movable}}));
  }
  for (const SolidPolygon& polygon : terrain.polygons) {
    nlohmann::json ring = nlohmann::json::array();
    for (const Point2& p : polygon.points) ring.push_back(Position(p));
    if (!polygon.points.empty()) ring.push_back(Position(polygon.points.front()));
    features.push_back(Feature(
        {{"type", "Polygon"}, {"coordinates", {ring}}},
        {{"kind", std::string(ObstacleKindName(polygon.kind))}, {"movable", polygon.movable}}));
  }
  for (const Door& door : terrain.doors) {
    features.push_back(
        Feature({{"type", "LineString"}, {"coordinates", {Position(door.a), Position(door.b)}}},
                {{"kind", "door"}, {"open", door.open}, {"thickness", door.thickness}}));
  }
  return {
      {"type", "FeatureCollection"},
      {"properties",
       {{"terrain", std::string(TerrainKindName(terrain.kind))},
        {"size", terrain.size},
        {"seed", terrain.seed},
        {"frame", "map"},
        {"start", {{"x", terrain.start.x}, {"y", terrain.start.y}, {"yaw", terrain.start.yaw}}}}},
      {"features", std::move(features)}};
}

std::string TerrainToGeoJsonString(const Terrain& terrain, int indent) {
  return TerrainToGeoJson(terrain).dump(indent);
}

}  // namespace fleetmap::sim
