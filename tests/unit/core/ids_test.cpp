#include "common/core/ids.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <unordered_set>

namespace fleetmap {
namespace {

TEST(TileIdTest, OrdersAndHashes) {
  EXPECT_LT((TileId{-1, 5}), (TileId{0, -3}));
  EXPECT_LT((TileId{0, -3}), (TileId{0, 2}));
  std::unordered_set<TileId> set = {{0, 0}, {0, 1}, {1, 0}, {-1, 0}, {0, 0}};
  EXPECT_EQ(set.size(), 4u);
  std::ostringstream os;
  os << TileId{3, -2};
  EXPECT_EQ(os.str(), "tile(3, -2)");
}

TEST(RobotIdTest, ValidNamesAreRosTokens) {
  EXPECT_TRUE(IsValidRobotName("robot_1"));
  EXPECT_TRUE(IsValidRobotName("R"));
  EXPECT_FALSE(IsValidRobotName(""));
  EXPECT_FALSE(IsValidRobotName("1robot"));
  EXPECT_FALSE(IsValidRobotName("robot/1"));
  EXPECT_FALSE(IsValidRobotName("robot-1"));
  EXPECT_FALSE(IsValidRobotName(std::string(65, 'a')));
}

}  // namespace
}  // namespace fleetmap
