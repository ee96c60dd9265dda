#include "common/core/sample_queue.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

namespace fleetmap {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST(SampleQueueTest, DrainsInArrivalOrderAndEmpties) {
  SampleQueue<int> queue(8);
  queue.Push(1);
  queue.Push(2);
  queue.Push(3);
  EXPECT_THAT(queue.Drain(), ElementsAre(1, 2, 3));
  EXPECT_THAT(queue.Drain(), IsEmpty());
  EXPECT_EQ(queue.dropped(), 0u);
}

TEST(SampleQueueTest, AFullQueueDropsTheOldestAndCountsIt) {
  SampleQueue<int> queue(3);
  for (int i = 1; i <= 5; ++i) queue.Push(i);
  EXPECT_EQ(queue.dropped(), 2u);
  // The newest items survive: a stalled worker still gets the latest state.
  EXPECT_THAT(queue.Drain(), ElementsAre(3, 4, 5));
  // Draining makes room again; the count is a total since the queue was made.
  queue.Push(6);
  queue.Push(7);
  queue.Push(8);
  EXPECT_EQ(queue.dropped(), 2u);
  queue.Push(9);
  EXPECT_EQ(queue.dropped(), 3u);
  EXPECT_THAT(queue.Drain(), ElementsAre(7, 8, 9));
}

TEST(SampleQueueTest, HoldsMoveOnlyItems) {
  SampleQueue<std::unique_ptr<int>> queue(1);
  queue.Push(std::make_unique<int>(1));
  queue.Push(std::make_unique<int>(2));
  std::vector<std::unique_ptr<int>> drained = queue.Drain();
  ASSERT_EQ(drained.size(), 1u);
  EXPECT_EQ(*drained[0], 2);
  EXPECT_EQ(queue.dropped(), 1u);
}

TEST(SampleQueueTest, CountsEveryPushFromManyThreads) {
  constexpr int kThreads = 4;
  constexpr int kPushes = 1000;
  SampleQueue<int> queue(100);
  std::vector<std::thread> producers;
  for (int t = 0; t < kThreads; ++t) {
    producers.emplace_back([&queue] {
      for (int i = 0; i < kPushes; ++i) queue.Push(i);
    });
  }
  for (std::thread& producer : producers) producer.join();
  const size_t kept = queue.Drain().size();
  EXPECT_EQ(kept, 100u);
  EXPECT_EQ(kept + queue.dropped(), static_cast<size_t>(kThreads * kPushes));
}

}  // namespace
}  // namespace fleetmap
