#include "common/grid/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace fleetmap::grid {
namespace {

TEST(OccupancyGridTest, StateOfFollowsThresholds) {
  EXPECT_EQ(StateOf(kUnknownValue), CellState::kUnknown);
  EXPECT_EQ(StateOf(0), CellState::kFree);
  EXPECT_EQ(StateOf(24), CellState::kFree);
  EXPECT_EQ(StateOf(25), CellState::kUnknown);
  EXPECT_EQ(StateOf(65), CellState::kUnknown);
  EXPECT_EQ(StateOf(66), CellState::kOccupied);
  EXPECT_EQ(StateOf(100), CellState::kOccupied);
  EXPECT_EQ(StateOf(101), CellState::kUnknown);
  EXPECT_EQ(StateOf(50, {.occupied = 0.4, .free = 0.1}), CellState::kOccupied);
}

// A resolution that crossed a float32 field is the same resolution; a real other one is not.
TEST(OccupancyGridTest, SameResolutionWithinAMillionth) {
  EXPECT_TRUE(SameResolution(0.05, 0.05));
  EXPECT_TRUE(SameResolution(0.05, static_cast<double>(0.05F)));  // 0.05000000074505806
  EXPECT_TRUE(SameResolution(static_cast<double>(0.025F), 0.025));
  EXPECT_FALSE(SameResolution(0.05, 0.0501));
  EXPECT_FALSE(SameResolution(0.05, 0.025));
  EXPECT_FALSE(SameResolution(0.05, 0.05 * (1.0 + 2e-6)));
}

TEST(OccupancyGridTest, CellCentreAndLookupAgree) {
  const OccupancyGrid grid(4, 3, 0.5, Pose2{-1.0, 2.0, 0.0});
  const Point2 centre = grid.CellCenter(2, 1);
  EXPECT_DOUBLE_EQ(centre.x(), 0.25);
  EXPECT_DOUBLE_EQ(centre.y(), 2.75);
  ASSERT_TRUE(grid.CellAt(centre).has_value());
  EXPECT_EQ(*grid.CellAt(centre), (CellIndex{2, 1}));
  EXPECT_FALSE(grid.CellAt(Point2(-1.01, 2.0)).has_value());
  EXPECT_FALSE(grid.CellAt(Point2(1.0, 2.0)).has_value());
}

TEST(OccupancyGridTest, RotatedOriginRotatesCells) {
  const OccupancyGrid grid(2, 2, 1.0, Pose2{0.0, 0.0, std::numbers::pi / 2});
  const Point2 centre = grid.CellCenter(1, 0);
  EXPECT_NEAR(centre.x(), -0.5, 1e-12);
  EXPECT_NEAR(centre.y(), 1.5, 1e-12);
  EXPECT_EQ(*grid.CellAt(centre), (CellIndex{1, 0}));
}

TEST(OccupancyGridTest, CountsStates) {
  OccupancyGrid grid(3, 2, 0.1);
  grid.at(0, 0) = kOccupiedValue;
  grid.at(1, 0) = kFreeValue;
  grid.at(2, 1) = kFreeValue;
  const StateCounts counts = grid.CountStates();
  EXPECT_EQ(counts.occupied, 1);
  EXPECT_EQ(counts.free, 2);
  EXPECT_EQ(counts.unknown, 3);
}

}  // namespace
}  // namespace fleetmap::grid
