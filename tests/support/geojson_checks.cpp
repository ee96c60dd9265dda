#include "tests/support/geojson_checks.hpp"

#include <geos_c.h>

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

void CheckCoordinates(const nlohmann::json& geometry, const std::string& where,
                      std::vector<std::string>* problems) {
  const std::string type = geometry.value("type", "");
  const nlohmann::json& coordinates = geometry["coordinates"];
  if (type == "LineString") CheckPositions(coordinates, false, where, problems);
  if (type == "MultiLineString") {
    for (const auto& line : coordinates) CheckPositions(line, false, where, problems);
  }
  if (type == "Polygon") {
    for (const auto& ring : coordinates) CheckPositions(ring, true, where, problems);
  }
  if (type == "MultiPolygon") {
    for (const auto& polygon : coordinates) {
      for (const auto& ring : polygon) CheckPositions(ring, true, where, problems);
    }
  }
}

}  // namespace

std::vector<std::string> GeoJsonProblems(const nlohmann::json& collection) {
  std::vector<std::string> problems;
  const nlohmann::json expected_crs = {{"type", "name"},
                                       {"properties", {{"name", "urn:ogc:def:crs:EPSG::3857"}}}};
  if (!collection.contains("crs") || collection["crs"] != expected_crs) {
    problems.push_back("no crs member naming EPSG:3857");
  }
  GEOSContextHandle_t h = GEOS_init_r();
  GEOSGeoJSONReader* reader = GEOSGeoJSONReader_create_r(h);
  const nlohmann::json& features = collection["features"];
  for (size_t i = 0; i < features.size(); ++i) {
    const nlohmann::json& geometry = features[i]["geometry"];
    std::string where = "feature ";
    where.append(std::to_string(i)).append(" (").append(geometry.value("type", "?")).append(")");
    CheckCoordinates(geometry, where, &problems);
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
