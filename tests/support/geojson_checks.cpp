#include "tests/support/geojson_checks.hpp"

#include <geodesic.h>
#include <geos_c.h>

#include <cmath>

namespace fleetmap::testing {
namespace {

using Positions = std::vector<nlohmann::json>;

// Ring rules GEOS's reader or validity test would not all report (repeated positions are valid
// to GEOS, but GIS profiles reject them and they say the writer is sloppy).
void CheckPositions(const nlohmann::json& positions, bool ring, const std::string& where,
                    std::vector<std::string>* problems) {
  if (ring && positions.size() < 4) problems->push_back(where + ": ring of fewer than 4 positions");
  if (ring && !positions.empty() && positions.front() != positions.back()) {
    problems->push_back(where + ": ring not closed");
  }
  for (size_t i = 1; i < positions.size(); ++i) {
    if (positions[i] == positions[i - 1]) {
      problems->push_back(where + ": repeated position " + positions[i].dump());
      return;
    }
  }
}

// The signed area of a closed ring, counter-clockwise positive: by the shoelace formula in
// metres, or geodesically on the WGS84 ellipsoid in degrees.
double SignedRingArea(const nlohmann::json& ring, GeoJsonCoordinates coordinates) {
  if (coordinates == GeoJsonCoordinates::kFrameMetres) {
    double twice = 0.0;
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      twice += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
               ring[i + 1][0].get<double>() * ring[i][1].get<double>();
    }
    return twice / 2.0;
  }
  geod_geodesic wgs84;
  geod_init(&wgs84, 6378137.0, 1.0 / 298.257223563);
  geod_polygon polygon;
  geod_polygon_init(&polygon, 0);
  for (size_t i = 0; i + 1 < ring.size(); ++i) {  // the closing position is implied
    geod_polygon_addpoint(&wgs84, &polygon, ring[i][1].get<double>(), ring[i][0].get<double>());
  }
  double area = 0.0;
  geod_polygon_compute(&wgs84, &polygon, /*reverse=*/0, /*sign=*/1, &area, nullptr);
  return area;
}

// RFC 7946 (3.1.6): exterior rings counter-clockwise, holes clockwise.
void CheckWinding(const nlohmann::json& rings, GeoJsonCoordinates coordinates,
                  const std::string& where, std::vector<std::string>* problems) {
  for (size_t k = 0; k < rings.size(); ++k) {
    if (rings[k].size() < 4) continue;  // reported as too short
    const double area = SignedRingArea(rings[k], coordinates);
    if (k == 0 && area < 0.0) problems->push_back(where + ": shell wound clockwise");
    if (k > 0 && area > 0.0) problems->push_back(where + ": hole wound counter-clockwise");
  }
}

void CheckRange(const nlohmann::json& coordinates, const std::string& where,
                std::vector<std::string>* problems) {
  if (coordinates.is_array() && !coordinates.empty() && coordinates[0].is_number()) {
    const double longitude = coordinates[0].get<double>();
    const double latitude = coordinates[1].get<double>();
    if (!(std::abs(longitude) <= 180.0 && std::abs(latitude) <= 90.0)) {
      problems->push_back(where + ": not a longitude and latitude: " + coordinates.dump());
    }
    return;
  }
  for (const auto& part : coordinates) CheckRange(part, where, problems);
}

void CheckCoordinates(const nlohmann::json& geometry, GeoJsonCoordinates kind,
                      const std::string& where, std::vector<std::string>* problems) {
  const std::string type = geometry.value("type", "");
  const nlohmann::json& coordinates = geometry["coordinates"];
  if (type == "LineString") CheckPositions(coordinates, false, where, problems);
  if (type == "MultiLineString") {
    for (const auto& line : coordinates) CheckPositions(line, false, where, problems);
  }
  if (type == "Polygon") {
    for (const auto& ring : coordinates) CheckPositions(ring, true, where, problems);
    CheckWinding(coordinates, kind, where, problems);
  }
  if (type == "MultiPolygon") {
    for (const auto& polygon : coordinates) {
      for (const auto& ring : polygon) CheckPositions(ring, true, where, problems);
      CheckWinding(polygon, kind, where, problems);
    }
  }
  if (kind == GeoJsonCoordinates::kWgs84) CheckRange(coordinates, where, problems);
}

}  // namespace

std::vector<std::string> GeoJsonProblems(const nlohmann::json& collection,
                                         GeoJsonCoordinates coordinates) {
  std::vector<std::string> problems;
  const nlohmann::json expected_crs = {{"type", "name"},
                                       {"properties", {{"name", "urn:ogc:def:crs:EPSG::3857"}}}};
  if (coordinates == GeoJsonCoordinates::kFrameMetres &&
      (!collection.contains("crs") || collection["crs"] != expected_crs)) {
    problems.push_back("no crs member naming EPSG:3857");
  }
  if (coordinates == GeoJsonCoordinates::kWgs84 && collection.contains("crs")) {
    problems.push_back("a crs member (RFC 7946 has none: WGS84 longitude and latitude only)");
  }
  GEOSContextHandle_t h = GEOS_init_r();
  GEOSGeoJSONReader* reader = GEOSGeoJSONReader_create_r(h);
  const nlohmann::json& features = collection["features"];
  for (size_t i = 0; i < features.size(); ++i) {
    const nlohmann::json& geometry = features[i]["geometry"];
    std::string where = "feature ";
    where.append(std::to_string(i)).append(" (").append(geometry.value("type", "?")).append(")");
    CheckCoordinates(geometry, coordinates, where, &problems);
    GEOSGeometry* read = GEOSGeoJSONReader_readGeometry_r(h, reader, geometry.dump().c_str());
    if (read == nullptr) {
      problems.push_back(where + ": GEOS cannot read it");
      continue;
    }
    if (GEOSisValid_r(h, read) != 1) {
      char* reason = GEOSisValidReason_r(h, read);
      problems.push_back(where + ": invalid: " + (reason != nullptr ? reason : "?"));
      GEOSFree_r(h, reason);
    }
    GEOSGeom_destroy_r(h, read);
  }
  GEOSGeoJSONReader_destroy_r(h, reader);
  GEOS_finish_r(h);
  return problems;
}

double PolygonArea(const nlohmann::json& collection, GeoJsonCoordinates coordinates) {
  double area = 0.0;
  const auto add_polygon = [&](const nlohmann::json& rings) {
    for (const auto& ring : rings) area += SignedRingArea(ring, coordinates);  // holes negative
  };
  for (const auto& feature : collection["features"]) {
    const nlohmann::json& geometry = feature["geometry"];
    const std::string type = geometry.value("type", "");
    if (type == "Polygon") add_polygon(geometry["coordinates"]);
    if (type == "MultiPolygon") {
      for (const auto& polygon : geometry["coordinates"]) add_polygon(polygon);
    }
  }
  return area;
}

int PolygonFeatureCount(const nlohmann::json& collection) {
  int count = 0;
  for (const auto& feature : collection["features"]) {
    const std::string type = feature["geometry"].value("type", "");
    count += type == "Polygon" || type == "MultiPolygon";
  }
  return count;
}

struct GeoJsonCoverage::Geos {
  GEOSContextHandle_t handle = GEOS_init_r();
  std::vector<GEOSGeometry*> geometries;
  std::vector<const GEOSPreparedGeometry*> prepared;
};

GeoJsonCoverage::GeoJsonCoverage(const nlohmann::json& collection)
    : geos_(std::make_unique<Geos>()) {
  GEOSGeoJSONReader* reader = GEOSGeoJSONReader_create_r(geos_->handle);
  for (const auto& feature : collection["features"]) {
    GEOSGeometry* geometry =
        GEOSGeoJSONReader_readGeometry_r(geos_->handle, reader, feature["geometry"].dump().c_str());
    if (geometry == nullptr) continue;  // GeoJsonProblems reports it
    geos_->geometries.push_back(geometry);
    geos_->prepared.push_back(GEOSPrepare_r(geos_->handle, geometry));
  }
  GEOSGeoJSONReader_destroy_r(geos_->handle, reader);
}

GeoJsonCoverage::~GeoJsonCoverage() {
  for (const GEOSPreparedGeometry* p : geos_->prepared)
    GEOSPreparedGeom_destroy_r(geos_->handle, p);
  for (GEOSGeometry* g : geos_->geometries) GEOSGeom_destroy_r(geos_->handle, g);
  GEOS_finish_r(geos_->handle);
}

bool GeoJsonCoverage::Covers(double x, double y, double tolerance) const {
  GEOSGeometry* point = GEOSGeom_createPointFromXY_r(geos_->handle, x, y);
  bool covered = false;
  for (const GEOSPreparedGeometry* p : geos_->prepared) {
    if (GEOSPreparedDistanceWithin_r(geos_->handle, p, point, tolerance) == 1) {
      covered = true;
      break;
    }
  }
  GEOSGeom_destroy_r(geos_->handle, point);
  return covered;
}

}  // namespace fleetmap::testing
