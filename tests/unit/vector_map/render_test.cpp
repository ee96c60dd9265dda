#include <gtest/gtest.h>

#include "common/vector_map/geojson.hpp"
#include "common/vector_map/png.hpp"
#include "common/vector_map/svg.hpp"
#include "common/vector_map/vectorizer.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

VectorMap SampleMap() {
  VectorMap map;
  map.epsilon = 0.07;
  map.resolution = 0.05;
  map.obstacles.push_back(Polyline{{Point2(0, 0), Point2(1, 0), Point2(1, 1)}, false, 0.035});
  map.obstacles.push_back(Polyline{{Point2(2, 2), Point2(3, 2), Point2(3, 3)}, true});
  map.obstacles.push_back(Polyline{{Point2(5, 5)}});
  map.free_space.push_back(FreePolygon{{Point2(0, 0), Point2(4, 0), Point2(4, 4), Point2(0, 4)},
                                       {{Point2(1, 1), Point2(2, 1), Point2(2, 2)}}});
  return map;
}

TEST(GeoJsonTest, WritesObstaclesAndFreeSpace) {
  const nlohmann::json json = ToGeoJson(SampleMap());
  EXPECT_EQ(json["type"], "FeatureCollection");
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
  EXPECT_EQ(nlohmann::json::parse(ToGeoJsonString(SampleMap())), json);
}

TEST(SvgTest, DrawsEveryPolyline) {
  const std::string svg = ToSvg(SampleMap());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("<polygon"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_NE(svg.find("evenodd"), std::string::npos);
}

TEST(PngTest, EncodesGridsAndVectorMaps) {
  const grid::OccupancyGrid grid = testing::FloorPlan();
  const auto png = EncodeGridPng(grid);
  ASSERT_TRUE(png.ok());
  ASSERT_GT(png->size(), 8u);
  EXPECT_EQ((*png)[1], 'P');
  EXPECT_EQ((*png)[2], 'N');
  const auto drawn = RenderVectorMapPng(*Vectorizer().Vectorize(grid), grid);
  ASSERT_TRUE(drawn.ok());
  EXPECT_EQ((*drawn)[1], 'P');
  EXPECT_FALSE(EncodeGridPng(grid::OccupancyGrid()).ok());
}

}  // namespace
}  // namespace fleetmap::vector_map
