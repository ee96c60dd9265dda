#pragma once

// GeoJSON pieces every fleetmap export shares (docs/file-formats.md, "Vector map pictures and
// exports"): positions, the `crs` member, and the geometries of a FilledArea.
//
// Coordinates are frame metres (the map or fleet frame), not WGS84 degrees. The `crs` member names
// EPSG:3857 (a projected CRS in metres), as nav2_route's graph files do, so that GIS tools read
// the numbers as metres on a plane instead of as longitude and latitude. For a frame surveyed on
// Earth, georeferenced_geojson.hpp turns such a collection into RFC 7946 longitude / latitude.

#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/types.hpp"
#include "common/gis/filled_area.hpp"

namespace fleetmap::gis {

inline constexpr const char* kGeoJsonCrsName = "urn:ogc:def:crs:EPSG::3857";

// {"type": "name", "properties": {"name": kGeoJsonCrsName}}: a FeatureCollection's "crs" member.
nlohmann::json GeoJsonCrs();

// A distance or coordinate in metres as the exports write it: rounded to the micrometre
// (kCoordinateDecimals, the grid FilledArea is snapped to), so that a vertex on a 0.025 m lattice
// is 42.175, not 42.175000000000004 (the float noise of i * quantum + origin).
double GeoJsonMetres(double value);

// [x, y], each GeoJsonMetres.
nlohmann::json GeoJsonPosition(const Point2& p);

// At most three geometries, in this order: a Polygon (MultiPolygon if the area has several
// parts), a LineString (MultiLineString) for the lines, a Point (MultiPoint) for the points.
// None for an empty area.
std::vector<nlohmann::json> GeoJsonGeometries(const FilledArea& area);

}  // namespace fleetmap::gis
