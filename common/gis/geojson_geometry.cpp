#include "common/gis/geojson_geometry.hpp"

#include <string>

#include "common/core/number_format.hpp"

namespace fleetmap::gis {
namespace {

// A FilledArea's positions as they are: already on the grid, or, where rounding would have made
// a polygon invalid, deliberately not (filled_area.hpp); rounding them again could undo that.
nlohmann::json Positions(const std::vector<Point2>& points) {
  nlohmann::json out = nlohmann::json::array();
  for (const Point2& p : points) out.push_back(nlohmann::json::array({p.x(), p.y()}));
  return out;
}

nlohmann::json PolygonCoordinates(const SimplePolygon& polygon) {
  nlohmann::json rings = nlohmann::json::array({Positions(polygon.shell)});
  for (const auto& hole : polygon.holes) rings.push_back(Positions(hole));
  return rings;
}

// A single part as `type`, several as its Multi form.
nlohmann::json SingleOrMulti(const std::string& type, nlohmann::json parts) {
  if (parts.size() == 1) return {{"type", type}, {"coordinates", std::move(parts[0])}};
  std::string multi = "Multi";
  multi.append(type);
  return {{"type", multi}, {"coordinates", std::move(parts)}};
}

}  // namespace

nlohmann::json GeoJsonCrs() {
  return {{"type", "name"}, {"properties", {{"name", kGeoJsonCrsName}}}};
}

double GeoJsonMetres(double value) { return RoundToDecimals(value, kCoordinateDecimals); }

nlohmann::json GeoJsonPosition(const Point2& p) {
  return nlohmann::json::array({GeoJsonMetres(p.x()), GeoJsonMetres(p.y())});
}

std::vector<nlohmann::json> GeoJsonGeometries(const FilledArea& area) {
  std::vector<nlohmann::json> out;
  if (!area.polygons.empty()) {
    nlohmann::json parts = nlohmann::json::array();
    for (const SimplePolygon& polygon : area.polygons) parts.push_back(PolygonCoordinates(polygon));
    out.push_back(SingleOrMulti("Polygon", std::move(parts)));
  }
  if (!area.lines.empty()) {
    nlohmann::json parts = nlohmann::json::array();
    for (const auto& line : area.lines) parts.push_back(Positions(line));
    out.push_back(SingleOrMulti("LineString", std::move(parts)));
  }
  if (!area.points.empty()) {
    out.push_back(SingleOrMulti("Point", Positions(area.points)));
  }
  return out;
}

}  // namespace fleetmap::gis
