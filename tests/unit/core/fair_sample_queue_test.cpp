#include "common/core/fair_sample_queue.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace fleetmap {
namespace {

using ::testing::ElementsAre;

TEST(FairSampleQueueTest, OneSourcesBacklogDoesNotStandInFrontOfAnothersItems) {
  FairSampleQueue<int> queue;
  for (int i = 0; i < 1000; ++i) queue.Push("flood", i);
  queue.Push("robot", -1);
  queue.Push("robot", -2);
  // The robot's items come within the first four, one per source in turn.
  EXPECT_THAT(queue.Drain(4), ElementsAre(0, -1, 1, -2));
  EXPECT_EQ(queue.size(), 998u);
  const std::vector<int> rest = queue.Drain();
  ASSERT_EQ(rest.size(), 998u);
  EXPECT_EQ(rest.front(), 2);  // oldest first within a source
  EXPECT_EQ(rest.back(), 999);
  EXPECT_EQ(queue.size(), 0u);
}

TEST(FairSampleQueueTest, TurnsGoOnFromWhereTheLastDrainEnded) {
  FairSampleQueue<int> queue;
  for (int i = 0; i < 3; ++i) {
    queue.Push("a", 10 + i);
    queue.Push("b", 20 + i);
    queue.Push("c", 30 + i);
  }
  EXPECT_THAT(queue.Drain(2), ElementsAre(10, 20));
  EXPECT_THAT(queue.Drain(2), ElementsAre(30, 11));
  EXPECT_THAT(queue.Drain(), ElementsAre(21, 31, 12, 22, 32));
}

TEST(FairSampleQueueTest, WhenFullTheSourceHoldingTheMostLosesItsOldest) {
  FairSampleQueue<int> queue(4);
  queue.Push("robot", 1);
  queue.Push("flood", 100);
  queue.Push("flood", 101);
  queue.Push("flood", 102);
  queue.Push("flood", 103);  // full: the flood's oldest goes, not the robot's
  queue.Push("robot", 2);    // full again: the flood still holds the most
  EXPECT_EQ(queue.dropped(), 2u);
  EXPECT_THAT(queue.Drain(), ElementsAre(102, 1, 103, 2));
}

}  // namespace
}  // namespace fleetmap
