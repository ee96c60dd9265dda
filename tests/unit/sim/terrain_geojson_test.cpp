#include "common/sim/terrain_geojson.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/sim/terrain_generator.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::sim {
namespace {

using ::testing::IsEmpty;

class TerrainGeoJsonTest : public ::testing::TestWithParam<TerrainKind> {};

// Furniture and rubble are simple polygons by construction: each is one valid Polygon feature,
// and the collection carries the crs member GIS tools need to read metres.
TEST_P(TerrainGeoJsonTest, EverySolidPolygonIsOneValidPolygonFeature) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    const Terrain terrain =
        TerrainGenerator::Create({.kind = GetParam(), .size = 30.0, .seed = seed})->Generate();
    const StatusOr<nlohmann::json> json = TerrainToGeoJson(terrain);
    ASSERT_TRUE(json.ok()) << json.status();
    EXPECT_THAT(fleetmap::testing::GeoJsonProblems(*json), IsEmpty()) << "seed " << seed;
    EXPECT_EQ(fleetmap::testing::PolygonFeatureCount(*json),
              static_cast<int>(terrain.polygons.size()))
        << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(All, TerrainGeoJsonTest,
                         ::testing::Values(TerrainKind::kMaze, TerrainKind::kOffice,
                                           TerrainKind::kUnstructured));

}  // namespace
}  // namespace fleetmap::sim
