#include <gtest/gtest.h>

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
