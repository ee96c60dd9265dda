#include "common/object_learning/region_splitter.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

namespace fleetmap::object_learning {
namespace {

std::vector<grid::CellIndex> Rectangle(int x0, int y0, int w, int h) {
  std::vector<grid::CellIndex> cells;
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) cells.push_back({x, y});
  }
  return cells;
}

size_t TotalCells(const SplitRegions& split) {
  size_t total = 0;
  for (const auto& part : split.parts) total += part.size();
  return total;
}

TEST(RegionSplitterTest, ARegionWithinTheLimitsStaysWhole) {
  const SplitRegions split = SplitRegion(Rectangle(0, 0, 10, 6), RegionLimits{100, 30});
  ASSERT_EQ(split.parts.size(), 1u);
  EXPECT_EQ(split.parts[0].size(), 60u);
  EXPECT_FALSE(split.sliced);
}

TEST(RegionSplitterTest, ObjectsJoinedByANarrowNeckAreCutAtTheNeck) {
  // Two 20 x 12 desks joined by a one-cell-wide strip (as region growing links nearby objects).
  std::vector<grid::CellIndex> cells = Rectangle(0, 0, 20, 12);
  for (const grid::CellIndex& c : Rectangle(30, 0, 20, 12)) cells.push_back(c);
  for (const grid::CellIndex& c : Rectangle(20, 5, 10, 1)) cells.push_back(c);
  const SplitRegions split = SplitRegion(cells, RegionLimits{300, 30});
  ASSERT_EQ(split.parts.size(), 2u);
  EXPECT_FALSE(split.sliced);
  EXPECT_EQ(TotalCells(split), cells.size());  // every cell kept, once
  for (const auto& part : split.parts) {
    EXPECT_GE(part.size(), 240u);
    EXPECT_LE(part.size(), 250u);
    // Each part holds one desk's cells only.
    std::set<bool> sides;
    for (const grid::CellIndex& c : part) {
      if (c.x < 20 || c.x >= 30) sides.insert(c.x >= 30);
    }
    EXPECT_EQ(sides.size(), 1u);
  }
}

TEST(RegionSplitterTest, PartsApartAreSeparatedBeforeAnythingElse) {
  std::vector<grid::CellIndex> cells = Rectangle(0, 0, 20, 12);
  for (const grid::CellIndex& c : Rectangle(22, 0, 20, 12)) cells.push_back(c);  // 2 cells apart
  const SplitRegions split = SplitRegion(cells, RegionLimits{300, 30});
  ASSERT_EQ(split.parts.size(), 2u);
  EXPECT_EQ(split.parts[0].size(), 240u);
  EXPECT_EQ(split.parts[1].size(), 240u);
}

TEST(RegionSplitterTest, ASolidRowIsSlicedWithinTheLimits) {
  // A row of touching desks drawn solid: no neck to cut at.
  const std::vector<grid::CellIndex> cells = Rectangle(0, 0, 120, 12);
  const RegionLimits limits{400, 30};
  const SplitRegions split = SplitRegion(cells, limits);
  EXPECT_TRUE(split.sliced);
  EXPECT_GE(split.parts.size(), 4u);
  EXPECT_EQ(TotalCells(split), cells.size());
  for (const auto& part : split.parts) {
    EXPECT_LE(static_cast<int>(part.size()), limits.max_cells);
    EXPECT_LE(RegionRadius(part), limits.max_radius_cells);
  }
}

}  // namespace
}  // namespace fleetmap::object_learning
