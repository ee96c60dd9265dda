#include "common/vector_map/geojson.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "common/vector_map/tiled_vector_map.hpp"
#include "tests/support/geojson_checks.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

using ::fleetmap::testing::GeoJsonProblems;
using ::fleetmap::testing::PolygonFeatureCount;
using ::testing::ElementsAre;
using ::testing::IsEmpty;

nlohmann::json Exported(const VectorMap& map) {
  StatusOr<nlohmann::json> json = ToGeoJson(map);
  EXPECT_TRUE(json.ok()) << json.status();
  return json.ok() ? *json : nlohmann::json::object();
}

std::vector<std::string> GeometryTypes(const nlohmann::json& collection, const std::string& kind) {
  std::vector<std::string> types;
  for (const auto& feature : collection["features"]) {
    if (feature["properties"]["kind"] == kind) types.push_back(feature["geometry"]["type"]);
  }
  return types;
}

// True if the rasterizer fills `p` from `polygon` as docs/vector-maps.md says it does: `p` is
// inside an odd number of its rings (the even-odd rule of cv::fillPoly), or on one of its
// outlines (within `tolerance`).
bool FreePolygonFills(const FreePolygon& polygon, const Point2& p, double tolerance) {
  std::vector<std::vector<Point2>> rings = {polygon.outer};
  rings.insert(rings.end(), polygon.holes.begin(), polygon.holes.end());
  bool inside = false;
  for (const auto& ring : rings) {
    for (size_t i = 0; i < ring.size(); ++i) {
      const Point2& a = ring[i];
      const Point2& b = ring[(i + 1) % ring.size()];
      const Point2 ab = b - a;
      const double t =
          ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((a + t * ab - p).norm() <= tolerance) return true;
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * ab.x() / ab.y()) {
        inside = !inside;
      }
    }
  }
  return inside;
}

// Cell centres of `like` (where the rasterizer decides a cell) that a free polygon of `map` fills
// and its exported features do not cover, or the other way round. Each polygon is exported and
// compared on its own, over its bounding box grown by a cell.
int CellCentresFilledDifferently(const VectorMap& map, const grid::OccupancyGrid& like) {
  // The export writes coordinates to the micrometre (gis::kCoordinateDecimals): a cell centre on
  // an outline is covered to that precision.
  const double tolerance = 1e-6;
  int differ = 0;
  for (const FreePolygon& polygon : map.free_space) {
    VectorMap one;
    one.free_space.push_back(polygon);
    const fleetmap::testing::GeoJsonCoverage exported(Exported(one));
    Eigen::AlignedBox2d box;
    for (const Point2& p : polygon.outer) box.extend(p);
    const auto low = like.CellAt(box.min() - Point2::Constant(like.resolution()));
    const auto high = like.CellAt(box.max() + Point2::Constant(like.resolution()));
    const int x0 = low ? low->x : 0, y0 = low ? low->y : 0;
    const int x1 = high ? high->x : like.width() - 1, y1 = high ? high->y : like.height() - 1;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Point2 c = like.CellCenter(x, y);
        differ +=
            FreePolygonFills(polygon, c, tolerance) != exported.Covers(c.x(), c.y(), tolerance);
      }
    }
  }
  return differ;
}

TEST(GeoJsonTest, WritesObstaclesAndFreeSpace) {
  const nlohmann::json json = Exported(testing::SmallVectorMap());
  EXPECT_EQ(json["type"], "FeatureCollection");
  EXPECT_EQ(json["crs"]["properties"]["name"], "urn:ogc:def:crs:EPSG::3857");
  EXPECT_DOUBLE_EQ(json["properties"]["epsilon"].get<double>(), 0.07);
  EXPECT_DOUBLE_EQ(json["properties"]["resolution"].get<double>(), 0.05);
  EXPECT_EQ(json["properties"]["frame"], "map");
  ASSERT_EQ(json["features"].size(), 4u);
  const auto& open = json["features"][0];
  EXPECT_EQ(open["properties"]["kind"], "obstacle");
  EXPECT_EQ(open["geometry"]["type"], "LineString");
  EXPECT_EQ(open["geometry"]["coordinates"].size(), 3u);
  EXPECT_EQ(json["features"][1]["geometry"]["coordinates"].size(), 4u);  // closed: repeats
  EXPECT_DOUBLE_EQ(open["properties"]["half_width"].get<double>(), 0.035);
  const auto& point = json["features"][2];
  EXPECT_EQ(point["properties"]["kind"], "obstacle");
  EXPECT_EQ(point["geometry"]["type"], "Point");
  EXPECT_EQ(point["geometry"]["coordinates"], nlohmann::json::array({5.0, 5.0}));
  const auto& free = json["features"][3];
  EXPECT_EQ(free["properties"]["kind"], "free");
  EXPECT_EQ(free["geometry"]["type"], "Polygon");
  ASSERT_EQ(free["geometry"]["coordinates"].size(), 2u);
  EXPECT_EQ(free["geometry"]["coordinates"][0].size(), 5u);
  EXPECT_EQ(free["geometry"]["coordinates"][0][0], free["geometry"]["coordinates"][0][4]);
  EXPECT_EQ(free["geometry"]["coordinates"][1].size(), 4u);
  EXPECT_THAT(GeoJsonProblems(json), IsEmpty());
  EXPECT_EQ(nlohmann::json::parse(*ToGeoJsonString(testing::SmallVectorMap())), json);
}

// Issue 33: vertices on a 0.025 m lattice, computed as i * quantum (1687 * 0.025 is
// 42.175000000000004), are written as the decimals they are, in the coordinates and the half
// width alike.
TEST(GeoJsonTest, WritesCoordinatesWithoutFloatNoise) {
  VectorMap map;
  map.epsilon = 0.07;
  map.resolution = 0.05;
  map.obstacles.push_back(
      Polyline{{Point2(1687 * 0.025, -3 * 12.8), Point2(0.1 + 0.2, 1687 * 0.025)}, false, 0.035});
  const StatusOr<std::string> text = ToGeoJsonString(map);
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_THAT(*text, ::testing::HasSubstr("[[42.175,-38.4],[0.3,42.175]]"));
  EXPECT_THAT(*text, ::testing::HasSubstr("\"half_width\":0.035"));
  EXPECT_THAT(*text, ::testing::Not(::testing::ContainsRegex("[0-9]\\.[0-9]{10}")));
}

// Rings as the free-space extractor makes them, through cell centres of a 1 m grid: a lone free
// cell, a row of free cells, a figure of eight touching itself at a cell, a room with a corridor
// one cell wide running out of it.
TEST(GeoJsonTest, DegenerateAndSelfTouchingFreeRingsExportValidAndCoverWhatTheyFill) {
  auto centre = [](int x, int y) { return Point2(x + 0.5, y + 0.5); };
  VectorMap map;
  map.resolution = 1.0;
  map.epsilon = 1.5;
  map.free_space.push_back({{centre(20, 20)}, {}});
  map.free_space.push_back({{centre(2, 20), centre(8, 20)}, {}});
  map.free_space.push_back({{centre(0, 0), centre(4, 0), centre(4, 4), centre(8, 4), centre(8, 8),
                             centre(4, 8), centre(4, 4), centre(0, 4)},
                            {}});
  map.free_space.push_back(
      {{centre(10, 0), centre(14, 0), centre(14, 4), centre(14, 9), centre(14, 4), centre(10, 4)},
       {}});
  const nlohmann::json json = Exported(map);
  EXPECT_THAT(GeoJsonProblems(json), IsEmpty());
  EXPECT_THAT(GeometryTypes(json, "free"),
              ElementsAre("Point", "LineString", "MultiPolygon", "Polygon", "LineString"));
  EXPECT_EQ(CellCentresFilledDifferently(map, grid::OccupancyGrid(30, 30, 1.0)), 0);
}

// What `fleetmap vectorize --geojson` writes (10 m tiles, merged) for each real map: GEOS finds
// every geometry valid, and the features fill the cells the map's free polygons fill.
class RealMapGeoJsonTest : public ::testing::TestWithParam<std::string> {};

TEST_P(RealMapGeoJsonTest, EveryGeometryIsValidAndCoversWhatTheMapFills) {
  grid::OccupancyGrid grid;
  if (!testing::LoadRealMap(GetParam(), grid)) GTEST_SKIP() << GetParam() << " not available";
  const StatusOr<TiledVectorMap> tiled = VectorizeTiled(grid, Transform2::Identity());
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  const VectorMap map = tiled->Merged();
  const nlohmann::json json = Exported(map);
  EXPECT_THAT(GeoJsonProblems(json), IsEmpty());
  EXPECT_GT(PolygonFeatureCount(json), 0);
  EXPECT_EQ(CellCentresFilledDifferently(map, grid), 0);
}

INSTANTIATE_TEST_SUITE_P(Maps, RealMapGeoJsonTest, ::testing::ValuesIn(testing::RealMapNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace fleetmap::vector_map
