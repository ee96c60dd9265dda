#include "robot_agent/server_watch.hpp"

#include <gtest/gtest.h>

namespace fleetmap::agent {
namespace {

using std::chrono::seconds;
const ServerWatch::Clock::time_point kStart{seconds(1000)};

TEST(ServerWatchTest, SaysOnceWhenNoServerWasSeenAndOnceWhenOneIs) {
  ServerWatch watch(std::chrono::milliseconds(10'000), kStart);
  EXPECT_FALSE(watch.Update(0, kStart + seconds(9)).has_value());
  const auto missing = watch.Update(0, kStart + seconds(10));
  ASSERT_TRUE(missing.has_value());
  EXPECT_NE(missing->find("no fleet server seen for 10 s"), std::string::npos) << *missing;
  EXPECT_TRUE(watch.missing());
  EXPECT_FALSE(watch.Update(0, kStart + seconds(30)).has_value());  // said once
  const auto seen = watch.Update(1, kStart + seconds(31));
  ASSERT_TRUE(seen.has_value());
  EXPECT_NE(seen->find("seen now"), std::string::npos) << *seen;
  EXPECT_FALSE(watch.missing());
}

TEST(ServerWatchTest, AServerThatGoesAwayIsReportedGoneAfterThePatience) {
  ServerWatch watch(std::chrono::milliseconds(2'000), kStart);
  EXPECT_FALSE(watch.Update(1, kStart + seconds(1)).has_value());  // found in time: nothing said
  EXPECT_FALSE(watch.Update(0, kStart + seconds(2)).has_value());
  const auto gone = watch.Update(0, kStart + seconds(3));
  ASSERT_TRUE(gone.has_value());
  EXPECT_NE(gone->find("gone for 2 s"), std::string::npos) << *gone;
  const auto back = watch.Update(2, kStart + seconds(4));
  ASSERT_TRUE(back.has_value());
  EXPECT_NE(back->find("back"), std::string::npos) << *back;
}

}  // namespace
}  // namespace fleetmap::agent
