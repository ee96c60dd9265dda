#include "common/object_learning/memory_plan.hpp"

#include <gtest/gtest.h>

namespace fleetmap::object_learning {
namespace {

TEST(MemoryPlanTest, LearningGrowsLinearlyInSnapshotsTimesPatchCells) {
  // Doubling the snapshots (objects fixed) at most doubles the estimate: no snapshots x objects x
  // cells table is held any more.
  const double base = LearningBytes(160, 40 * 40, 40, 10, 12);
  EXPECT_LE(LearningBytes(320, 40 * 40, 40, 10, 12), 2.0 * base);
  EXPECT_LE(LearningBytes(160, 80 * 80, 40, 10, 12), 4.0 * base);
  // 160 snapshots of 211 x 211 cells, 40 objects (the 10 GB case) fit in 1 GB now.
  EXPECT_LT(LearningBytes(160, 211 * 211, 40, 12, 12), 1e9);
}

TEST(MemoryPlanTest, CoarseningKeepsTheCentreAndHalvesTheSide) {
  SnapshotSet set;
  Snapshot snapshot;
  snapshot.patch.width = snapshot.patch.height = 21;
  snapshot.patch.resolution = 0.05;
  snapshot.patch.occupancy.assign(21 * 21, 0.0f);
  snapshot.patch.weight.assign(21 * 21, 1.0f);
  for (int y = 8; y <= 12; ++y) {
    for (int x = 8; x <= 12; ++x) snapshot.patch.at(x, y) = 1.0f;  // a 5 x 5 block at the centre
  }
  set.snapshots.push_back(snapshot);
  CoarsenSnapshots(&set);
  const scene::Patch& p = set.snapshots[0].patch;
  EXPECT_EQ(p.width, 11);
  EXPECT_EQ(p.height, 11);
  EXPECT_DOUBLE_EQ(p.resolution, 0.1);
  EXPECT_FLOAT_EQ(p.at(5, 5), 1.0f);  // the centre stays on the centre
  EXPECT_FLOAT_EQ(p.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(p.at(3, 5), 0.0f);  // old cell 6: outside the block and its smoothing
  EXPECT_GT(p.at(4, 5), 0.0f);        // old cell 8: the block's edge
}

}  // namespace
}  // namespace fleetmap::object_learning
