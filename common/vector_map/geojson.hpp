#pragma once

// GeoJSON export of a vector map (RFC 7946 structure, coordinates in map-frame metres, not WGS84):
// a FeatureCollection whose obstacle polylines are LineString features with "kind": "obstacle" (a
// closed polyline repeats its first vertex; a point obstacle is a zero-length LineString of two
// equal positions) and whose free space is Polygon features with "kind": "free". Top-level
// "properties" carry epsilon, resolution and frame.

#include <string>

#include <nlohmann/json.hpp>

#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

nlohmann::json ToGeoJson(const VectorMap& map);
// indent < 0 gives the compact form.
std::string ToGeoJsonString(const VectorMap& map, int indent = -1);

}  // namespace fleetmap::vector_map
