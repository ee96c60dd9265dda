#include "bench/extrapolation/floor_plan.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace fleetmap::bench {
namespace {

// The open doorways between neighbouring rooms are marked (scored for neither room: which one
// the generator labels them is a coin flip), and nothing else is.
TEST(FloorPlanTest, MarksTheDoorwaysBetweenRoomsAndNothingElse) {
  FloorPlanOptions always;
  always.connecting_doorway_probability = 1.0;
  FloorPlanOptions never = always;
  never.connecting_doorway_probability = 0.0;
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const StatusOr<FloorPlan> with = GenerateFloorPlan(always, seed);
    const StatusOr<FloorPlan> without = GenerateFloorPlan(never, seed);
    ASSERT_TRUE(with.ok() && without.ok());
    ASSERT_EQ(with->between_rooms.size(), with->labels.size());
    ASSERT_GT(with->connecting_doorways, 0);
    int64_t marked = 0;
    for (size_t i = 0; i < with->labels.size(); ++i) {
      if (!with->between_rooms[i]) continue;
      ++marked;
      EXPECT_GE(with->labels[i], 0) << "a marked cell is in a room's free space";
    }
    // A doorway of 0.8-0.9 m through a wall of 0.15 m or more: at least 16 x 3 cells each.
    EXPECT_GE(marked, 48 * with->connecting_doorways);
    for (uint8_t m : without->between_rooms) ASSERT_EQ(m, 0);
  }
}

}  // namespace
}  // namespace fleetmap::bench
