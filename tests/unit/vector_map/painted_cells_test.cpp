#include "common/vector_map/painted_cells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace fleetmap::vector_map {
namespace {

TEST(PaintedCellsTest, OneVisitFillsBothMasksAsTwoCallsDo) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-3.0, 43.0);
  std::uniform_real_distribution<double> half_width(0.0, 1.5);
  const grid::CellRect rect{0, 0, 40, 30};
  std::vector<CellPolyline> polylines;
  std::vector<double> radii;
  for (int k = 0; k < 30; ++k) {
    CellPolyline polyline;
    const int n = 1 + k % 5;
    for (int i = 0; i < n; ++i) {
      // Half-cell positions too, so that cells at exactly a radius occur.
      polyline.points.emplace_back(std::round(coordinate(rng) * 2.0) / 2.0,
                                   std::round(coordinate(rng) * 2.0) / 2.0);
    }
    polyline.closed = k % 3 == 0;
    polylines.push_back(polyline);
    radii.push_back(k % 4 == 0 ? 1.0 : half_width(rng));
  }
  const double near_radius = std::sqrt(2.0);
  std::vector<uint8_t> painted;
  std::vector<uint8_t> near = {1, 2, 3};  // storage is reused: old contents must not leak
  PaintedAndNearCells(rect, polylines, radii, 0.5, near_radius, &painted, &near);
  const std::vector<uint8_t> expected_painted = PaintedCells(rect, polylines, radii, 0.5);
  const std::vector<uint8_t> expected_near = PaintedCells(rect, polylines, {}, near_radius);
  EXPECT_EQ(painted, expected_painted);
  EXPECT_EQ(near, expected_near);
  int marked = 0;
  for (const uint8_t cell : near) marked += cell;
  EXPECT_GT(marked, 0);
}

}  // namespace
}  // namespace fleetmap::vector_map
