#include "common/gis/georeferenced_geojson.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "common/core/number_format.hpp"
#include "common/gis/filled_area.hpp"
#include "common/gis/geojson_geometry.hpp"

namespace fleetmap::gis {
namespace {

using Positions = std::vector<Point2>;  // longitude, latitude

// Frame-metre positions to WGS84 at full precision, each checked to lie on the origin's side of
// the antimeridian.
class Placer {
 public:
  explicit Placer(const Georeference& georeference) : georeference_(georeference) {}

  // [x, y] in metres -> (longitude, latitude) in degrees.
  StatusOr<Point2> Place(const nlohmann::json& position) const {
    if (!position.is_array() || position.size() < 2 || !position[0].is_number() ||
        !position[1].is_number()) {
      return InvalidArgumentError("a position is not [x, y]: " + position.dump());
    }
    const Point2 p_frame(position[0].get<double>(), position[1].get<double>());
    FLEETMAP_ASSIGN_OR_RETURN(const LonLat lon_lat, georeference_.ToLonLat(p_frame));
    // Seen from the origin, the point is `east` degrees of longitude away; past +-180 in total it
    // lies across the antimeridian, where RFC 7946 (3.1.9) wants lines and rings cut in two.
    const double origin_longitude = georeference_.origin().longitude;
    const double east = std::remainder(lon_lat.longitude - origin_longitude, 360.0);
    if (std::abs(origin_longitude + east) > 180.0) {
      return InvalidArgumentError("the point (" + FixedNumber(p_frame.x(), 3) + ", " +
                                  FixedNumber(p_frame.y(), 3) +
                                  ") m lies across the antimeridian (longitude 180) from the "
                                  "origin; RFC 7946 wants geometry cut there, which fleetmap does "
                                  "not do");
    }
    return Point2(lon_lat.longitude, lon_lat.latitude);
  }

  StatusOr<Positions> PlaceAll(const nlohmann::json& positions) const {
    if (!positions.is_array()) {
      return InvalidArgumentError("coordinates are not an array: " + positions.dump());
    }
    Positions out;
    for (const nlohmann::json& position : positions) {
      FLEETMAP_ASSIGN_OR_RETURN(const Point2 placed, Place(position));
      out.push_back(placed);
    }
    return out;
  }

 private:
  const Georeference& georeference_;
};

Point2 OnGrid(const Point2& lon_lat) {
  return {RoundToDecimals(lon_lat.x(), kDegreeDecimals),
          RoundToDecimals(lon_lat.y(), kDegreeDecimals)};
}

Positions WithoutRepeats(const Positions& positions, bool on_grid) {
  Positions out;
  for (const Point2& p : positions) {
    const Point2 q = on_grid ? OnGrid(p) : p;
    if (out.empty() || q != out.back()) out.push_back(q);
  }
  return out;
}

// A line on the degree grid, repeats dropped; as it is where rounding would leave it one position
// (as FilledArea keeps its lines), and a point where even that is one position: a line a rounding
// error long in metres (FilledArea writes such) that the transform's own rounding made a point.
void AddLine(const Positions& line, FilledArea* area) {
  Positions on_grid = WithoutRepeats(line, true);
  if (on_grid.size() >= 2) {
    area->lines.push_back(std::move(on_grid));
    return;
  }
  Positions exact = WithoutRepeats(line, false);
  if (exact.size() >= 2) {
    area->lines.push_back(std::move(exact));
  } else if (!exact.empty()) {
    area->points.push_back(OnGrid(exact.front()));
  }
}

// The rings of a Polygon's coordinates in degrees, open (FilledAreaOfRings closes them).
Status AddRings(const Placer& placer, const nlohmann::json& polygon,
                std::vector<Positions>* rings) {
  if (!polygon.is_array()) return InvalidArgumentError("a polygon is not an array of rings");
  for (const nlohmann::json& ring : polygon) {
    FLEETMAP_ASSIGN_OR_RETURN(Positions placed, placer.PlaceAll(ring));
    if (placed.size() > 1 && placed.front() == placed.back()) placed.pop_back();
    rings->push_back(std::move(placed));
  }
  return Status::Ok();
}

// The geometry in WGS84 as valid simple features. Points and lines are placed one by one; the
// area of a (Multi)Polygon is made again from its placed rings by FilledAreaOfRings on the degree
// grid, so that it is valid and wound per RFC 7946 in degrees, where it was in metres: a vertex
// that lay exactly on another part's edge in metres lies a rounding error beside it in degrees,
// and rounding to kDegreeDecimals moves vertices by up to half a millimetre. The point set is the
// same, so one geometry may come back as a polygon and a line or point.
StatusOr<std::vector<nlohmann::json>> GeoreferencedGeometries(const nlohmann::json& geometry,
                                                              const Placer& placer) {
  static const nlohmann::json kNoCoordinates = nlohmann::json::array();
  const std::string type = geometry.value("type", "");
  const nlohmann::json& coordinates =
      geometry.contains("coordinates") ? geometry["coordinates"] : kNoCoordinates;
  FilledArea area;
  if (type == "Point") {
    FLEETMAP_ASSIGN_OR_RETURN(const Point2 placed, placer.Place(coordinates));
    area.points.push_back(OnGrid(placed));
  } else if (type == "MultiPoint") {
    FLEETMAP_ASSIGN_OR_RETURN(const Positions placed, placer.PlaceAll(coordinates));
    for (const Point2& p : placed) area.points.push_back(OnGrid(p));
  } else if (type == "LineString") {
    FLEETMAP_ASSIGN_OR_RETURN(const Positions placed, placer.PlaceAll(coordinates));
    AddLine(placed, &area);
  } else if (type == "MultiLineString" && coordinates.is_array()) {
    for (const nlohmann::json& line : coordinates) {
      FLEETMAP_ASSIGN_OR_RETURN(const Positions placed, placer.PlaceAll(line));
      AddLine(placed, &area);
    }
  } else if (type == "Polygon" || (type == "MultiPolygon" && coordinates.is_array())) {
    std::vector<Positions> rings;
    if (type == "Polygon") {
      FLEETMAP_RETURN_IF_ERROR(AddRings(placer, coordinates, &rings));
    } else {
      // Parts of a valid MultiPolygon do not overlap, so the even-odd rule over all their rings
      // fills their union.
      for (const nlohmann::json& polygon : coordinates) {
        FLEETMAP_RETURN_IF_ERROR(AddRings(placer, polygon, &rings));
      }
    }
    FLEETMAP_ASSIGN_OR_RETURN(area, FilledAreaOfRings(rings, kDegreeDecimals));
  } else {
    return InvalidArgumentError("geometry type \"" + type + "\" is not one fleetmap writes");
  }
  return GeoJsonGeometries(area);
}

}  // namespace

StatusOr<nlohmann::json> GeoreferencedGeoJson(const nlohmann::json& collection,
                                              const Georeference& georeference) {
  if (!collection.is_object() || collection.value("type", "") != "FeatureCollection" ||
      !collection.contains("features") || !collection["features"].is_array()) {
    return InvalidArgumentError("not a GeoJSON FeatureCollection");
  }
  const Placer placer(georeference);
  nlohmann::json out = collection;
  out.erase("crs");
  nlohmann::json features = nlohmann::json::array();
  const nlohmann::json& given = collection["features"];
  for (size_t i = 0; i < given.size(); ++i) {
    if (!given[i].contains("geometry") || given[i]["geometry"].is_null()) {
      features.push_back(given[i]);  // a feature without geometry (RFC 7946, 3.2)
      continue;
    }
    StatusOr<std::vector<nlohmann::json>> geometries =
        GeoreferencedGeometries(given[i]["geometry"], placer);
    if (!geometries.ok()) return geometries.status().WithContext("feature " + std::to_string(i));
    for (nlohmann::json& geometry : *geometries) {
      nlohmann::json feature = given[i];
      feature["geometry"] = std::move(geometry);
      features.push_back(std::move(feature));
    }
  }
  out["features"] = std::move(features);
  const GeoOrigin& origin = georeference.origin();
  if (!out.contains("properties") || !out["properties"].is_object()) {
    out["properties"] = nlohmann::json::object();
  }
  out["properties"]["georeference"] = {
      {"latitude", origin.latitude}, {"longitude", origin.longitude}, {"yaw", origin.yaw}};
  return out;
}

}  // namespace fleetmap::gis
