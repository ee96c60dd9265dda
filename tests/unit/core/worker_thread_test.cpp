#include "common/core/worker_thread.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

namespace fleetmap {
namespace {

using std::chrono::milliseconds;

// Polls `done` (a test never asserts a duration; this only bounds a hang).
template <typename Done>
bool Eventually(Done done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(milliseconds(1));
  }
  return true;
}

TEST(WorkerThreadTest, RunsARoundWhenWokenAndAtStopOnceOnItsThread) {
  WorkerThread worker(std::nullopt);  // no timeout: only a wake starts a round
  std::atomic<int> rounds{0};
  std::atomic<int> stops{0};
  std::thread::id round_thread;
  std::thread::id stop_thread;
  std::mutex mutex;
  worker.Start(
      [&] {
        std::lock_guard lock(mutex);
        round_thread = std::this_thread::get_id();
        ++rounds;
        return false;
      },
      [&] {
        std::lock_guard lock(mutex);
        stop_thread = std::this_thread::get_id();
        ++stops;
      });
  worker.Wake();
  ASSERT_TRUE(Eventually([&] { return rounds.load() >= 1; }));
  worker.Stop();
  // The wake that Stop() sends ends the wait; that round runs, then at_stop, once.
  EXPECT_EQ(stops.load(), 1);
  EXPECT_GE(rounds.load(), 2);
  EXPECT_TRUE(worker.stopping());
  std::lock_guard lock(mutex);
  EXPECT_NE(round_thread, std::this_thread::get_id());
  EXPECT_EQ(stop_thread, round_thread);
  worker.Stop();  // idempotent
  EXPECT_EQ(stops.load(), 1);
}

TEST(WorkerThreadTest, ARoundWithWorkLeftIsFollowedAtOnce) {
  WorkerThread worker(std::nullopt);
  std::atomic<int> left{5};
  worker.Start([&] { return left.fetch_sub(1) > 1; });
  worker.Wake();  // one wake, then five rounds without another
  EXPECT_TRUE(Eventually([&] { return left.load() <= 0; }));
  worker.Stop();
}

TEST(WorkerThreadTest, ATimeoutStartsRoundsWithoutAWake) {
  WorkerThread worker(milliseconds(1));
  std::atomic<int> rounds{0};
  worker.Start([&] {
    ++rounds;
    return false;
  });
  EXPECT_TRUE(Eventually([&] { return rounds.load() >= 3; }));
  worker.Stop();
}

TEST(WorkerThreadTest, ANotifyOnItsWakeUpStartsARound) {
  WorkerThread worker(std::nullopt);
  std::atomic<int> rounds{0};
  worker.Start([&] {
    ++rounds;
    return false;
  });
  worker.wake_up()->Notify();  // what a reader's listener does
  EXPECT_TRUE(Eventually([&] { return rounds.load() >= 1; }));
  worker.Stop();
}

TEST(WorkerThreadTest, StopBeforeStartIsHarmless) {
  WorkerThread worker(milliseconds(10));
  worker.Stop();
  EXPECT_TRUE(worker.stopping());
}

}  // namespace
}  // namespace fleetmap
