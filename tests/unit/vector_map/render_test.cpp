#include <gtest/gtest.h>

#include "common/vector_map/png.hpp"
#include "common/vector_map/svg.hpp"
#include "common/vector_map/vectorizer.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

TEST(SvgTest, DrawsEveryPolyline) {
  const std::string svg = ToSvg(testing::SmallVectorMap());
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
