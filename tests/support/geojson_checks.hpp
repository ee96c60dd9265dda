#pragma once

// What a GIS tool (GDAL, QGIS, shapely: all GEOS underneath) would object to in a GeoJSON
// FeatureCollection that fleetmap wrote. The tests judge our exports with GEOS itself, reading
// each feature's geometry with GEOS's own GeoJSON reader, so they do not share the writer's code.

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fleetmap::testing {

// What a collection's positions are: frame metres with the EPSG:3857 `crs` member (fleetmap's
// default), or WGS84 longitude and latitude per RFC 7946 (`--georef`), which has no `crs` member.
enum class GeoJsonCoordinates { kFrameMetres, kWgs84 };

// One line per problem, naming the feature: for kFrameMetres no "crs" member naming EPSG:3857, for
// kWgs84 a "crs" member at all or a position outside [-180, 180] x [-90, 90]; a geometry GEOS
// cannot read or judges invalid (GEOSisValidReason: self-intersection, hole outside its shell,
// ...); a polygon ring not closed or of fewer than four positions, or wound against RFC 7946
// (shells counter-clockwise, holes clockwise); repeated consecutive positions.
std::vector<std::string> GeoJsonProblems(
    const nlohmann::json& collection,
    GeoJsonCoordinates coordinates = GeoJsonCoordinates::kFrameMetres);

// The area of a collection's Polygon and MultiPolygon features, holes taken out: in square metres
// on the plane for frame metres (the shoelace formula), and on the WGS84 ellipsoid for longitude
// and latitude (GeographicLib's geodesic polygon area, from PROJ's geodesic.h), so that the two
// exports of one map can be compared without the code that made them.
double PolygonArea(const nlohmann::json& collection, GeoJsonCoordinates coordinates);

// Polygon and MultiPolygon features (the polygons GIS tools count).
int PolygonFeatureCount(const nlohmann::json& collection);

// The point set of a collection's features as GEOS reads them, to ask which points they cover
// (inside an area, or on a line or point, within a tolerance).
class GeoJsonCoverage {
 public:
  explicit GeoJsonCoverage(const nlohmann::json& collection);
  ~GeoJsonCoverage();
  GeoJsonCoverage(const GeoJsonCoverage&) = delete;
  GeoJsonCoverage& operator=(const GeoJsonCoverage&) = delete;

  bool Covers(double x, double y, double tolerance) const;

 private:
  struct Geos;
  std::unique_ptr<Geos> geos_;
};

}  // namespace fleetmap::testing
