#pragma once

// The exact geometry of a terrain as GeoJSON (RFC 7946 structure, coordinates in map-frame metres,
// not WGS84): a FeatureCollection with one feature per wall (LineString of its centre line,
// properties kind = "wall" | "boundary", thickness, movable), per solid polygon (Polygon, ring
// closed by repeating the first vertex, kind = "furniture" | "rubble", movable) and per door
// (LineString across the doorway, kind = "door", open). Top-level properties: terrain kind, size,
// seed, start pose.

#include <string>

#include <nlohmann/json.hpp>

#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

nlohmann::json TerrainToGeoJson(const Terrain& terrain);
// indent < 0 gives the compact form.
std::string TerrainToGeoJsonString(const Terrain& terrain, int indent = -1);

}  // namespace fleetmap::sim
