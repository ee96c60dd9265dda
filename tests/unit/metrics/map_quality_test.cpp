#include "common/metrics/map_quality.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace fleetmap::metrics {
namespace {

using grid::OccupancyGrid;

// 'o' occupied, 'f' free, 'u' unknown; first string is row y = 0 (no flip needed here).
OccupancyGrid Grid(const std::vector<std::string>& rows) {
  OccupancyGrid grid(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()), 0.1);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const char c = rows[y][x];
      grid.at(x, y) =
          c == 'o' ? grid::kOccupiedValue : (c == 'f' ? grid::kFreeValue : grid::kUnknownValue);
    }
  }
  return grid;
}

TEST(MapQualityTest, IdenticalMapsScoreOneHundred) {
  const OccupancyGrid g = Grid({"ofu", "ffo"});
  const QualityScores s = *CompareMaps(g, g);
  EXPECT_DOUBLE_EQ(*s.map_score, 100.0);
  EXPECT_NEAR(*s.cross_correlation, 100.0, 1e-9);
  EXPECT_NEAR(*s.pearson_occupied, 100.0, 1e-9);
  EXPECT_DOUBLE_EQ(*s.occupied_picture_distance, 100.0);
  EXPECT_DOUBLE_EQ(*s.unoccupied_picture_distance, 100.0);
}

TEST(MapQualityTest, HandComputedTwoByTwo) {
  // R = [o f; u f], G = [o o; f f] (row-major). Values R = 1 0 .5 0, G = 1 1 0 0.
  const OccupancyGrid r = Grid({"of", "uf"});
  const OccupancyGrid g = Grid({"oo", "ff"});
  const QualityScores s = *CompareMaps(r, g);
  EXPECT_DOUBLE_EQ(*s.map_score, 50.0);  // cells 0 and 3 agree
  // mean R = 0.375, mean G = 0.5, mean RG = 0.25; var R = (1 + .25)/4 - .140625 = .171875,
  // var G = .25. CC = 100 * (.25 - .1875) / sqrt(.171875 * .25).
  EXPECT_NEAR(*s.cross_correlation, 100.0 * 0.0625 / std::sqrt(0.171875 * 0.25), 1e-9);
  // Indicators R = 1 0 0 0, G = 1 1 0 0: cov = .25 - .125, std R = sqrt(3)/4, std G = .5.
  EXPECT_NEAR(*s.pearson_occupied, 100.0 * 0.125 / (std::sqrt(3.0) / 4 * 0.5), 1e-9);
  // OPDF: R's only occupied cell is occupied in G: d = 0.
  EXPECT_DOUBLE_EQ(*s.occupied_picture_distance, 100.0);
  // UPDF: R free cells (1,0) and (1,1); G free cells are row 1: d = 1 and 0. r = sqrt(800).
  EXPECT_NEAR(*s.unoccupied_picture_distance, 100.0 * (1.0 - 1.0 / (2 * std::sqrt(800.0))), 1e-9);
}

TEST(MapQualityTest, WindowBoundsTheSearch) {
  // One occupied cell in R at x = 0, in G at x = 7: Manhattan 7.
  OccupancyGrid r(12, 1, 0.1, {}, grid::kFreeValue);
  OccupancyGrid g = r;
  r.at(0, 0) = grid::kOccupiedValue;
  g.at(7, 0) = grid::kOccupiedValue;
  QualityOptions wide;  // 20 x 20: offsets up to 10
  EXPECT_NEAR(*OccupiedPictureDistance(r, g, wide).value(), 100.0 * (1 - 7 / std::hypot(20, 20)),
              1e-9);
  QualityOptions narrow;
  narrow.window_width = 10;  // offsets up to 5: no match, pays r
  narrow.window_height = 4;
  EXPECT_NEAR(*OccupiedPictureDistance(r, g, narrow).value(), 0.0, 1e-9);
}

TEST(MapQualityTest, ManhattanDistanceUsesBothAxes) {
  OccupancyGrid r(9, 9, 0.1, {}, grid::kUnknownValue);
  OccupancyGrid g = r;
  r.at(4, 4) = grid::kOccupiedValue;
  g.at(6, 1) = grid::kOccupiedValue;  // |dx| + |dy| = 2 + 3
  EXPECT_NEAR(*OccupiedPictureDistance(r, g).value(), 100.0 * (1 - 5 / std::hypot(20, 20)), 1e-9);
}

TEST(MapQualityTest, UndefinedCasesAreEmptyNotOneHundred) {
  const OccupancyGrid unknown(3, 3, 0.1);
  const QualityScores s = *CompareMaps(unknown, unknown);
  EXPECT_DOUBLE_EQ(*s.map_score, 100.0);
  EXPECT_FALSE(s.cross_correlation.has_value());  // constant maps
  EXPECT_FALSE(s.pearson_occupied.has_value());
  EXPECT_FALSE(s.occupied_picture_distance.has_value());  // no occupied cell in R
  EXPECT_FALSE(s.unoccupied_picture_distance.has_value());

  const OccupancyGrid empty(0, 0, 0.1);
  const QualityScores e = *CompareMaps(empty, empty);
  EXPECT_FALSE(e.map_score.has_value());
  EXPECT_FALSE(e.cross_correlation.has_value());

  const OccupancyGrid all_occupied(2, 2, 0.1, {}, grid::kOccupiedValue);
  const QualityScores o = *CompareMaps(all_occupied, all_occupied);
  EXPECT_DOUBLE_EQ(*o.occupied_picture_distance, 100.0);
  EXPECT_FALSE(o.pearson_occupied.has_value());
  EXPECT_FALSE(o.unoccupied_picture_distance.has_value());

  const OccupancyGrid one(1, 1, 0.1, {}, grid::kFreeValue);
  const QualityScores single = *CompareMaps(one, one);
  EXPECT_DOUBLE_EQ(*single.map_score, 100.0);
  EXPECT_DOUBLE_EQ(*single.unoccupied_picture_distance, 100.0);
  EXPECT_FALSE(single.cross_correlation.has_value());
}

TEST(MapQualityTest, RejectsDifferentGeometry) {
  const OccupancyGrid a(3, 3, 0.1);
  EXPECT_EQ(CompareMaps(a, OccupancyGrid(3, 4, 0.1)).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(CompareMaps(a, OccupancyGrid(3, 3, 0.2)).status().code(), StatusCode::kInvalidArgument);
  QualityOptions bad;
  bad.window_width = 0;
  EXPECT_FALSE(MapScore(a, a, bad).ok());
}

}  // namespace
}  // namespace fleetmap::metrics
