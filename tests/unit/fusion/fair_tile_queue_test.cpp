#include "common/fusion/fair_tile_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

namespace fleetmap::fusion {
namespace {

using std::chrono::milliseconds;

// A turn target so long that only max_items bounds a turn (once a robot's cost is known).
constexpr auto kLong = std::chrono::hours(1);

TEST(FairTileQueueTest, ANewerRevisionOfAQueuedTileReplacesIt) {
  FairTileQueue<int> queue;
  queue.Push(RobotId{"alpha"}, {0, 0}, 1);
  queue.Push(RobotId{"alpha"}, {1, 0}, 2);
  queue.Push(RobotId{"alpha"}, {0, 0}, 3);
  EXPECT_EQ(queue.size(), 2u);
  RobotId robot;
  // The first turn is one tile (its cost unknown), in arrival order: the newer revision of (0, 0).
  EXPECT_EQ(queue.NextTurn(10, kLong, &robot), (std::vector<int>{3}));
  EXPECT_EQ(robot.value, "alpha");
  queue.Charge(robot, milliseconds(1), 1);
  EXPECT_EQ(queue.NextTurn(10, kLong, &robot), (std::vector<int>{2}));
  EXPECT_TRUE(queue.empty());
}

TEST(FairTileQueueTest, AFloodingRobotDoesNotDelayAnotherBeyondOneTurn) {
  FairTileQueue<int> queue;
  for (int i = 0; i < 1000; ++i) queue.Push(RobotId{"flood"}, {i, 0}, i);
  RobotId robot;
  // The flood's first turn (one tile while its cost is unknown) is expensive...
  ASSERT_EQ(queue.NextTurn(8, kLong, &robot).size(), 1u);
  queue.Charge(robot, milliseconds(100), 1);
  // ...then an honest robot's update arrives: it is served next, not after 992 tiles.
  queue.Push(RobotId{"honest"}, {5, 5}, -1);
  EXPECT_EQ(queue.NextTurn(8, kLong, &robot), (std::vector<int>{-1}));
  EXPECT_EQ(robot.value, "honest");
  queue.Charge(robot, milliseconds(2), 1);
  // With nobody else waiting the flood goes on, in turns as long as the target allows.
  EXPECT_EQ(queue.NextTurn(8, kLong, &robot).size(), 8u);
  EXPECT_EQ(robot.value, "flood");
}

TEST(FairTileQueueTest, RobotsWithEqualCostsTakeTurns) {
  FairTileQueue<int> queue;
  for (int i = 0; i < 4; ++i) {
    queue.Push(RobotId{"a"}, {i, 0}, i);
    queue.Push(RobotId{"b"}, {i, 0}, 10 + i);
  }
  std::string served;
  for (int turn = 0; turn < 4; ++turn) {
    RobotId robot;
    ASSERT_EQ(queue.NextTurn(1, kLong, &robot).size(), 1u);
    queue.Charge(robot, milliseconds(5), 1);
    served += robot.value;
  }
  EXPECT_EQ(served, "abab");
}

TEST(FairTileQueueTest, IdleTimeIsNotCredit) {
  FairTileQueue<int> queue;
  RobotId robot;
  queue.Push(RobotId{"a"}, {0, 0}, 0);
  queue.NextTurn(1, kLong, &robot);
  queue.Charge(RobotId{"a"}, milliseconds(1000), 1);
  // b arrives late: it starts level with a's progress, not 1000 ms behind it.
  queue.Push(RobotId{"a"}, {1, 0}, 1);
  queue.Push(RobotId{"b"}, {0, 0}, 2);
  queue.NextTurn(1, kLong, &robot);
  queue.Charge(robot, milliseconds(10), 1);
  const RobotId first = robot;
  queue.NextTurn(1, kLong, &robot);
  EXPECT_NE(first, robot);
}

TEST(FairTileQueueTest, ExpensiveTilesMakeShortTurns) {
  FairTileQueue<int> queue;
  for (int i = 0; i < 100; ++i) {
    queue.Push(RobotId{"cheap"}, {i, 0}, i);
    queue.Push(RobotId{"costly"}, {i, 0}, i);
  }
  RobotId robot;
  // Unknown cost: one item.
  EXPECT_EQ(queue.NextTurn(16, milliseconds(10), &robot).size(), 1u);
  const std::string first = robot.value;
  queue.Charge(robot, milliseconds(first == "cheap" ? 1 : 50), 1);
  EXPECT_EQ(queue.NextTurn(16, milliseconds(10), &robot).size(), 1u);
  queue.Charge(robot, milliseconds(robot.value == "cheap" ? 1 : 50), 1);
  // Known costs: 10 items of 1 ms fit in 10 ms, but never less than one item of 50 ms.
  const std::string cheap = "cheap";
  std::map<std::string, size_t> sizes;
  for (int turn = 0; turn < 40 && !queue.empty(); ++turn) {
    const auto items = queue.NextTurn(16, milliseconds(10), &robot);
    sizes[robot.value] = std::max(sizes[robot.value], items.size());
    queue.Charge(robot,
                 milliseconds(robot.value == cheap ? 1 : 50) * static_cast<int>(items.size()),
                 items.size());
  }
  EXPECT_EQ(sizes["cheap"], 10u);
  EXPECT_EQ(sizes["costly"], 1u);
}

TEST(FairTileQueueTest, TurnsFollowARiseInCostAtOnceAndAFallSlowly) {
  FairTileQueue<int> queue;
  for (int i = 0; i < 1000; ++i) queue.Push(RobotId{"a"}, {i, 0}, i);
  RobotId robot;
  ASSERT_EQ(queue.NextTurn(16, milliseconds(20), &robot).size(), 1u);
  queue.Charge(robot, milliseconds(2), 1);
  ASSERT_EQ(queue.NextTurn(16, milliseconds(20), &robot).size(), 10u);
  // The tiles turn four times as costly: the next turn is sized by that, not by an average.
  queue.Charge(robot, milliseconds(80), 10);
  EXPECT_EQ(queue.NextTurn(16, milliseconds(20), &robot).size(), 2u);
  // Cheap again: the turns grow back over a few turns, not at once.
  queue.Charge(robot, milliseconds(4), 2);
  const size_t after_one = queue.NextTurn(16, milliseconds(20), &robot).size();
  EXPECT_GT(after_one, 2u);
  EXPECT_LT(after_one, 10u);
  queue.Charge(robot, milliseconds(2) * static_cast<int>(after_one), after_one);
  size_t later = 0;
  for (int turn = 0; turn < 60; ++turn) {
    later = queue.NextTurn(16, milliseconds(20), &robot).size();
    queue.Charge(robot, milliseconds(2) * static_cast<int>(later), later);
  }
  EXPECT_EQ(later, 10u);
}

TEST(FairTileQueueTest, ErasedTilesAreNotServed) {
  FairTileQueue<int> queue;
  queue.Push(RobotId{"a"}, {0, 0}, 1);
  queue.Push(RobotId{"a"}, {1, 0}, 2);
  queue.Erase(RobotId{"a"}, {0, 0});
  queue.Erase(RobotId{"a"}, {7, 7});  // not queued: nothing happens
  RobotId robot;
  EXPECT_EQ(queue.NextTurn(10, kLong, &robot), (std::vector<int>{2}));
  EXPECT_TRUE(queue.empty());
}

}  // namespace
}  // namespace fleetmap::fusion
