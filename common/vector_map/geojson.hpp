#pragma once

// GeoJSON export of a vector map, for GIS tools (docs/file-formats.md, "Vector map pictures and
// exports"): a FeatureCollection in frame metres, with a `crs` member naming EPSG:3857 so that
// tools read metres, not degrees. Obstacle polylines are LineString features with "kind":
// "obstacle" (a closed polyline repeats its first vertex; a point obstacle is a Point). Free space
// is "kind": "free" features of valid simple-feature geometry (common/gis/filled_area.hpp): the
// area a free polygon fills as a Polygon (MultiPolygon where a self-touching ring splits it), and
// what fills no area (rings of one or two vertices, spikes one cell wide) as (Multi)LineString and
// (Multi)Point features. Top-level "properties" carry epsilon, resolution and frame.
//
// The repair is the export's alone: the in-memory map keeps its rings as the rasterizer reads
// them. gis::GeoreferencedGeoJson places the result on Earth (WGS84) for `--georef`.

#include <string>

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

// Errors (kInternal) only if GEOS fails on a free polygon; the message names it.
StatusOr<nlohmann::json> ToGeoJson(const VectorMap& map);
// indent < 0 gives the compact form.
StatusOr<std::string> ToGeoJsonString(const VectorMap& map, int indent = -1);

}  // namespace fleetmap::vector_map
