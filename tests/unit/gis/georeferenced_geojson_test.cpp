// A frame-metre GeoJSON export turned into RFC 7946 WGS84: no crs member, [longitude, latitude]
// to 8 decimals, winding and validity kept (judged by GEOS and by geodesic areas, not by the
// writer's code), areas preserved, refusals named.

#include "common/gis/georeferenced_geojson.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/gis/filled_area.hpp"
#include "common/gis/geojson_geometry.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::gis {
namespace {

using ::testing::ContainsRegex;
using testing::GeoJsonCoordinates;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

Georeference Make(const GeoOrigin& origin) {
  StatusOr<Georeference> made = Georeference::Create(origin);
  EXPECT_TRUE(made.ok()) << made.status();
  return std::move(made).value();
}

nlohmann::json Feature(nlohmann::json geometry, nlohmann::json properties = {{"kind", "free"}}) {
  return {{"type", "Feature"}, {"properties", properties}, {"geometry", std::move(geometry)}};
}

// What the exports write: a room of 40 x 30 m with a 10 x 10 m pillar (its area through
// FilledAreaOfRings and GeoJsonGeometries, as the exports make it), a wall and a speck.
nlohmann::json Room() {
  const StatusOr<FilledArea> area =
      FilledAreaOfRings({{{0.0, 0.0}, {40.0, 0.0}, {40.0, 30.0}, {0.0, 30.0}},
                         {{10.0, 10.0}, {10.0, 20.0}, {20.0, 20.0}, {20.0, 10.0}}});
  EXPECT_TRUE(area.ok()) << area.status();
  nlohmann::json features = nlohmann::json::array();
  for (nlohmann::json& geometry : GeoJsonGeometries(*area)) {
    features.push_back(Feature(std::move(geometry)));
  }
  features.push_back(Feature({{"type", "LineString"}, {"coordinates", {{0, -0.5}, {40, -0.5}}}},
                             {{"kind", "obstacle"}, {"half_width", 0.05}}));
  features.push_back(Feature({{"type", "Point"}, {"coordinates", {35.025, 5.075}}},
                             {{"kind", "obstacle"}, {"half_width", 0.05}}));
  return {{"type", "FeatureCollection"},
          {"crs", GeoJsonCrs()},
          {"properties", {{"epsilon", 0.0707}, {"frame", "fleet"}}},
          {"features", features}};
}

TEST(GeoreferencedGeoJsonTest, TheRoomIsRfc7946Wgs84NearTheOrigin) {
  const nlohmann::json plane = Room();
  ASSERT_THAT(testing::GeoJsonProblems(plane), IsEmpty());
  const StatusOr<nlohmann::json> placed =
      GeoreferencedGeoJson(plane, Make({.latitude = 48.8583, .longitude = 2.2945, .yaw = 30.0}));
  ASSERT_TRUE(placed.ok()) << placed.status();
  EXPECT_FALSE(placed->contains("crs"));
  EXPECT_THAT(testing::GeoJsonProblems(*placed, GeoJsonCoordinates::kWgs84), IsEmpty());
  ASSERT_EQ((*placed)["features"].size(), plane["features"].size());
  // Longitude first, within the room's 50 m of the origin (a metre is 1e-5 degree or more).
  const nlohmann::json& speck = (*placed)["features"].back()["geometry"]["coordinates"];
  EXPECT_NEAR(speck[0].get<double>(), 2.2945, 1e-3);
  EXPECT_NEAR(speck[1].get<double>(), 48.8583, 1e-3);
  // The properties stay (lengths in metres), and say where the frame is.
  EXPECT_EQ((*placed)["features"].back()["properties"]["half_width"], 0.05);
  EXPECT_EQ((*placed)["properties"]["frame"], "fleet");
  EXPECT_EQ((*placed)["properties"]["georeference"],
            nlohmann::json({{"latitude", 48.8583}, {"longitude", 2.2945}, {"yaw", 30.0}}));
  // 8 decimals of a degree at most.
  EXPECT_THAT(placed->dump(), Not(ContainsRegex("[0-9]\\.[0-9]{9}")));
}

// Rotation and the azimuthal equidistant projection keep areas and orientation: the geodesic area
// on the ellipsoid is the plane's 1100 m2, to the rounding of millimetre positions (0.2 m2 covers
// a millimetre along every edge), at every yaw
// and in every quarter of the globe (a reflection would make it -1100).
TEST(GeoreferencedGeoJsonTest, AreasAndWindingSurviveAtAnyYawAndPlace) {
  const nlohmann::json plane = Room();
  const double plane_area = testing::PolygonArea(plane, GeoJsonCoordinates::kFrameMetres);
  ASSERT_NEAR(plane_area, 1100.0, 1e-9);
  for (const GeoOrigin& origin : {GeoOrigin{.latitude = 48.8583, .longitude = 2.2945, .yaw = 0},
                                  GeoOrigin{.latitude = -33.45, .longitude = -70.66, .yaw = 135},
                                  GeoOrigin{.latitude = 0.0, .longitude = 0.0, .yaw = -90},
                                  GeoOrigin{.latitude = 78.2, .longitude = 15.6, .yaw = 200}}) {
    const StatusOr<nlohmann::json> placed = GeoreferencedGeoJson(plane, Make(origin));
    ASSERT_TRUE(placed.ok()) << placed.status();
    EXPECT_THAT(testing::GeoJsonProblems(*placed, GeoJsonCoordinates::kWgs84), IsEmpty())
        << origin.latitude;
    EXPECT_NEAR(testing::PolygonArea(*placed, GeoJsonCoordinates::kWgs84), plane_area, 0.2)
        << origin.latitude;
  }
}

// Rounded to 1e-8 degree (1.1 mm of latitude, 0.76 mm of longitude at 47 N): a triangle 0.1 mm
// tall would be flat (invalid), so it keeps its positions' full precision; a line whose first step
// is 0.1 mm loses that step; a line 10 um long (both ends in one 1e-8 degree cell) keeps its
// digits; a line one float step long (FilledArea writes such outlines a rounding error long) comes
// out as a line or, where the transform makes its ends one position, a point, never a line of one
// position; the wall beside them is rounded.
TEST(GeoreferencedGeoJsonTest, WhatRoundingWouldBreakKeepsItsDigits) {
  const nlohmann::json plane = {
      {"type", "FeatureCollection"},
      {"crs", GeoJsonCrs()},
      {"features",
       {Feature({{"type", "Polygon"}, {"coordinates", {{{0, 0}, {10, 0}, {5, 0.0001}, {0, 0}}}}}),
        Feature({{"type", "LineString"}, {"coordinates", {{0, 5}, {0.0001, 5}, {10, 5}}}}),
        Feature({{"type", "LineString"}, {"coordinates", {{3, 6}, {3.00001, 6}}}}),
        Feature({{"type", "LineString"}, {"coordinates", {{0, 8}, {10, 8}}}}),
        Feature({{"type", "MultiLineString"},
                 {"coordinates",
                  {{{21.075000000000003, 8.275}, {21.075000000000003, 8.274999999999999}},
                   {{5, 7}, {6, 7}}}}})}}};
  ASSERT_THAT(testing::GeoJsonProblems(plane), IsEmpty());
  const StatusOr<nlohmann::json> placed =
      GeoreferencedGeoJson(plane, Make({.latitude = 47.0, .longitude = 8.0, .yaw = 0.0}));
  ASSERT_TRUE(placed.ok()) << placed.status();
  EXPECT_THAT(testing::GeoJsonProblems(*placed, GeoJsonCoordinates::kWgs84), IsEmpty());
  const auto& features = (*placed)["features"];
  ASSERT_GE(features.size(), 5u) << features.dump();
  EXPECT_EQ(features[0]["geometry"]["type"], "Polygon");
  EXPECT_THAT(features[0]["geometry"].dump(), ContainsRegex("[0-9]\\.[0-9]{10}"));
  EXPECT_EQ(features[1]["geometry"]["coordinates"].size(), 2u);
  EXPECT_THAT(features[1]["geometry"].dump(), Not(ContainsRegex("[0-9]\\.[0-9]{9}")));
  EXPECT_THAT(features[2]["geometry"].dump(), ContainsRegex("[0-9]\\.[0-9]{10}"));
  EXPECT_EQ(features[3]["geometry"]["type"], "LineString");
  EXPECT_THAT(features[3]["geometry"].dump(), Not(ContainsRegex("[0-9]\\.[0-9]{9}")));
  for (size_t i = 4; i < features.size(); ++i) {
    EXPECT_THAT(features[i]["geometry"]["type"],
                ::testing::AnyOf("LineString", "MultiLineString", "Point"));
  }
}

// About 7.6 m west of the antimeridian on the equator, a 100 m wall reaches across it: RFC 7946
// would have it cut in two there, which the export does not do, so it says so.
TEST(GeoreferencedGeoJsonTest, GeometryAcrossTheAntimeridianIsRefused) {
  const nlohmann::json plane = {
      {"type", "FeatureCollection"},
      {"features",
       {Feature({{"type", "Point"}, {"coordinates", {0, 0}}}),
        Feature({{"type", "LineString"}, {"coordinates", {{0, 0}, {100, 0}}}})}}};
  const StatusOr<nlohmann::json> placed =
      GeoreferencedGeoJson(plane, Make({.latitude = 0.0, .longitude = 179.99993, .yaw = 0.0}));
  ASSERT_FALSE(placed.ok());
  EXPECT_EQ(placed.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(placed.status().message(), HasSubstr("feature 1"));
  EXPECT_THAT(placed.status().message(), HasSubstr("(100, 0) m lies across the antimeridian"));
  // Going west from there is fine.
  EXPECT_TRUE(
      GeoreferencedGeoJson(plane, Make({.latitude = 0.0, .longitude = 179.99993, .yaw = 180.0}))
          .ok());
}

TEST(GeoreferencedGeoJsonTest, InputsItCannotReadAreRefused) {
  const Georeference georeference = Make({.latitude = 1.0, .longitude = 2.0, .yaw = 0.0});
  EXPECT_THAT(GeoreferencedGeoJson({{"type", "Feature"}}, georeference).status().message(),
              HasSubstr("not a GeoJSON FeatureCollection"));
  const nlohmann::json collection = {
      {"type", "FeatureCollection"},
      {"features", {Feature({{"type", "GeometryCollection"}, {"geometries", {}}})}}};
  EXPECT_THAT(GeoreferencedGeoJson(collection, georeference).status().message(),
              HasSubstr("feature 0: geometry type \"GeometryCollection\""));
  const nlohmann::json bad_position = {
      {"type", "FeatureCollection"},
      {"features", {Feature({{"type", "Point"}, {"coordinates", {"a", 1}}})}}};
  EXPECT_THAT(GeoreferencedGeoJson(bad_position, georeference).status().message(),
              HasSubstr("feature 0: a position is not [x, y]"));
}

}  // namespace
}  // namespace fleetmap::gis
