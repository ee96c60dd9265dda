#pragma once

// The exact geometry of a terrain as GeoJSON (RFC 7946 structure, coordinates in map-frame metres,
// not WGS84, with a `crs` member naming EPSG:3857 so that GIS tools read metres): a
// FeatureCollection with one feature per wall (LineString of its centre line, properties kind =
// "wall" | "boundary", thickness, movable), per solid polygon (kind = "furniture" | "rubble",
// movable; valid simple-feature geometry made by common/gis/filled_area.hpp: a Polygon, closed,
// counter-clockwise) and per door (LineString across the doorway, kind = "door", open). Top-level
// properties: terrain kind, size, seed, start pose.

#include <string>

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

// Errors (kInternal) only if GEOS fails on a polygon; the message names it.
StatusOr<nlohmann::json> TerrainToGeoJson(const Terrain& terrain);
// indent < 0 gives the compact form.
StatusOr<std::string> TerrainToGeoJsonString(const Terrain& terrain, int indent = -1);

}  // namespace fleetmap::sim
