// The vectorizer on the real maps of ../shared/data/maps (SOURCES.md), loaded with map_io; in a
// lone clone, on the three copied into tests/data/maps/real.

#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <string>

#include <opencv2/imgproc.hpp>

#include "common/metrics/map_quality.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "common/vector_map/validator.hpp"
#include "common/vector_map/vectorizer.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

grid::OccupancyGrid Load(const std::string& name) {
  grid::OccupancyGrid grid;
  if (!testing::LoadRealMap(name, grid)) return grid::OccupancyGrid();
  return grid;
}

// The baseline of SOURCES.md: findContours(RETR_LIST, CHAIN_APPROX_SIMPLE) + approxPolyDP(1.414).
size_t OpenCvVertices(const grid::OccupancyGrid& grid) {
  cv::Mat mask(grid.height(), grid.width(), CV_8UC1);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      mask.at<uint8_t>(y, x) = grid.StateAt(x, y) == grid::CellState::kOccupied ? 255 : 0;
    }
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
  size_t vertices = 0;
  for (const auto& contour : contours) {
    std::vector<cv::Point> simplified;
    cv::approxPolyDP(contour, simplified, 1.414, true);
    vertices += simplified.size();
  }
  return vertices;
}

class RealMapTest : public ::testing::TestWithParam<std::string> {};

TEST_P(RealMapTest, DefaultMethodHoldsBothConstraintsAndRoundTrips) {
  const grid::OccupancyGrid grid = Load(GetParam());
  if (grid.empty()) GTEST_SKIP() << "map " << GetParam() << " not available";
  const VectorMap map = *Vectorizer().Vectorize(grid);
  ValidatorOptions validator_options;
  validator_options.measure_segment_distance = false;
  const ValidationReport report = *Validator(validator_options).Validate(map, grid);
  EXPECT_EQ(report.uncovered_points, 0);
  EXPECT_EQ(report.discontinuous_segments, 0);

  const size_t ours = map.ObstacleVertexCount();
  const size_t opencv = OpenCvVertices(grid);
  // Regression guard at the measured level (docs/results.md): at most 0.95 x OpenCV per map.
  EXPECT_LE(static_cast<double>(ours), 0.95 * static_cast<double>(opencv));

  const grid::OccupancyGrid back = *Rasterizer().Rasterize(map, grid);
  EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, map, back), 0);
  const auto scores = *metrics::CompareMaps(back, grid);
  std::cout << GetParam() << ": vertices " << ours << " (OpenCV " << opencv << "), free vertices "
            << map.FreeVertexCount() << ", P " << report.delimitation_points << ", MS "
            << *scores.map_score << ", OPDF " << *scores.occupied_picture_distance << ", UPDF "
            << *scores.unoccupied_picture_distance << "\n";
  // Regression guards at the measured levels (docs/results.md); the target of 99 % for MS
  // and OPDF is not met yet on every map (see docs/vector-maps.md, "Round trip").
  EXPECT_GE(*scores.map_score, 97.0);
  EXPECT_GE(*scores.occupied_picture_distance, 98.3);
  EXPECT_GE(*scores.unoccupied_picture_distance, 99.8);
}

// What a .vmap carries: 10 m tiles, free space included. Free-space size is guarded by its ring
// and vertex counts (4 bytes a vertex, 4 a ring on the wire), at the measured level plus 5 %.
TEST_P(RealMapTest, TiledFreeSpaceStaysSmallAndRoundTrips) {
  const grid::OccupancyGrid grid = Load(GetParam());
  if (grid.empty()) GTEST_SKIP() << "map " << GetParam() << " not available";
  const TiledVectorMap tiled = *VectorizeTiled(grid, Transform2::Identity());
  const VectorMap merged = tiled.Merged();
  size_t rings = 0;
  for (const FreePolygon& polygon : merged.free_space) rings += 1 + polygon.holes.size();
  const size_t free_bytes = 4 * (rings + merged.FreeVertexCount());
  // Measured free-space bytes. Before occupied cells within epsilon of an edge were don't care
  // (every unpainted occupied cell was a hole or a notch): 25364, 32996, 6268, 10608, 4888, 1356,
  // 460; before any occupied cell left unpainted was guarded (they came back free): 14084, 18872,
  // 3816, 10592, 2068, 540, 336; before obstacles and occupied cells were don't care for free
  // space: 64524, 92600, 7196, 16576, 5784, 1428, 384.
  static const std::map<std::string, size_t> kMeasured = {
      {"intel_lab", 14096},     {"aces3_austin", 18848},
      {"nav2_warehouse", 3816}, {"willow_garage_2010", 10592},
      {"strands_kth", 2060},    {"aws_small_house", 548},
      {"tb3_world", 336}};
  std::cout << GetParam() << ": tiled free rings " << rings << ", free vertices "
            << merged.FreeVertexCount() << ", free bytes " << free_bytes << "\n";
  EXPECT_LE(static_cast<double>(free_bytes), 1.05 * static_cast<double>(kMeasured.at(GetParam())));
  const grid::OccupancyGrid back = *Rasterizer().Rasterize(merged, grid);
  EXPECT_EQ(testing::OccupiedFarFromObstaclesComeBackFree(grid, merged, back), 0);
  const auto scores = *metrics::CompareMaps(back, grid);
  EXPECT_GE(*scores.map_score, 97.5);
  EXPECT_GE(*scores.occupied_picture_distance, 98.4);
  EXPECT_GE(*scores.unoccupied_picture_distance, 99.8);
}

INSTANTIATE_TEST_SUITE_P(Maps, RealMapTest, ::testing::ValuesIn(testing::RealMapNames()),
                         [](const auto& info) { return info.param; });

TEST(RealMapTileTest, TilesOfARealMapHoldTheConstraintsTogether) {
  const grid::OccupancyGrid grid = Load("strands_kth");
  if (grid.empty()) GTEST_SKIP() << "map strands_kth not available";
  const int tile = 64;
  VectorizerOptions options;
  options.extract_free_space = false;
  const Vectorizer vectorizer(options);
  VectorMap whole;
  for (int y = 0; y < grid.height(); y += tile) {
    for (int x = 0; x < grid.width(); x += tile) {
      const CellRect rect{x, y, std::min(tile, grid.width() - x),
                          std::min(tile, grid.height() - y)};
      const VectorMap part = *vectorizer.VectorizeTile(grid, rect);
      whole.epsilon = part.epsilon;
      whole.Append(part);
    }
  }
  ValidatorOptions validator_options;
  validator_options.measure_segment_distance = false;
  const ValidationReport report = *Validator(validator_options).Validate(whole, grid);
  EXPECT_TRUE(report.ok()) << report.uncovered_points << " " << report.discontinuous_segments;
}

}  // namespace
}  // namespace fleetmap::vector_map
