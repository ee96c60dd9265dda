// SegmentMemo: the clearance map's segment checks, remembered until the clearance under them
// changes; what it forgets and what it keeps.
#include "common/route_graph/segment_memo.hpp"

#include <gtest/gtest.h>

#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

using testing::Fill;
using testing::SolidGrid;

TEST(SegmentMemoTest, AnswersAsTheClearanceMapAndForgetsOnlyWhatAChangeReaches) {
  grid::OccupancyGrid grid = SolidGrid(20.0, 4.0);
  Fill(&grid, 0.5, 0.5, 19.5, 3.5);  // a hall 19 x 3 m
  ClearanceMap clearance(grid, 3.0);
  SegmentMemo memo;
  const Point2 west_a(1.5, 2.0), west_b(5.0, 2.0);    // far from the change below
  const Point2 east_a(12.0, 2.0), east_b(16.0, 2.0);  // through it
  EXPECT_EQ(memo.Keeps(clearance, west_a, west_b, 0.5),
            clearance.SegmentKeeps(west_a, west_b, 0.5));
  EXPECT_TRUE(memo.Keeps(clearance, east_a, east_b, 0.5));
  EXPECT_DOUBLE_EQ(memo.Clearance(clearance, east_a, east_b),
                   clearance.SegmentClearance(east_a, east_b));
  EXPECT_EQ(memo.size(), 3u);

  // A pallet put down on the east segment.
  Fill(&grid, 13.8, 1.8, 14.2, 2.2, grid::kOccupiedValue);
  const grid::CellRect changed{270, 30, 20, 20};  // cells of x 13.5-14.5 m, y 1.5-2.5 m
  clearance.Update(grid, changed);
  ASSERT_FALSE(clearance.SegmentKeeps(east_a, east_b, 0.5));
  // Remembered until told: a memo, not a cache that watches the map.
  EXPECT_TRUE(memo.Keeps(clearance, east_a, east_b, 0.5));
  memo.Forget(changed);
  EXPECT_EQ(memo.size(), 1u) << "the west segment does not read the changed cells";
  EXPECT_FALSE(memo.Keeps(clearance, east_a, east_b, 0.5));
  EXPECT_DOUBLE_EQ(memo.Clearance(clearance, east_a, east_b),
                   clearance.SegmentClearance(east_a, east_b));
  EXPECT_TRUE(memo.Keeps(clearance, west_a, west_b, 0.5));
  memo.Clear();
  EXPECT_EQ(memo.size(), 0u);
}

}  // namespace
}  // namespace fleetmap::route_graph
