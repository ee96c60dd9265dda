#pragma once

// What a GIS tool (GDAL, QGIS, shapely: all GEOS underneath) would object to in a GeoJSON
// FeatureCollection that fleetmap wrote. The tests judge our exports with GEOS itself, reading
// each feature's geometry with GEOS's own GeoJSON reader, so they do not share the writer's code.

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fleetmap::testing {

// One line per problem, naming the feature: no "crs" member naming EPSG:3857 (metres); a geometry
// GEOS cannot read or judges invalid (GEOSisValidReason: self-intersection, hole outside its shell,
// ...); a polygon ring not closed or of fewer than four positions; repeated consecutive positions.
std::vector<std::string> GeoJsonProblems(const nlohmann::json& collection);

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
