#include "view/event_broadcaster.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <thread>

namespace fleetmap::view {
namespace {

using std::chrono::milliseconds;

Event Text(const std::string& text) { return std::make_shared<const std::string>(text); }

std::string NextText(EventBroadcaster& broadcaster, EventBroadcaster::Client& client) {
  const std::optional<Event> event = broadcaster.Next(client, milliseconds(10));
  if (!event) return "<closed>";
  if (*event == nullptr) return "<nothing>";
  return **event;
}

TEST(EventBroadcasterTest, ANewClientGetsTheWholeStateThenDeltas) {
  EventBroadcaster broadcaster;
  auto client = broadcaster.Connect();
  ASSERT_NE(client, nullptr);
  EXPECT_TRUE(broadcaster.WantsFullState());
  // A delta without a whole state is not for it: it waits for one.
  broadcaster.Publish(Text("d1"), nullptr);
  EXPECT_EQ(NextText(broadcaster, *client), "<nothing>");
  broadcaster.Publish(Text("d2"), Text("full2"));
  broadcaster.Publish(Text("d3"), nullptr);
  EXPECT_FALSE(broadcaster.WantsFullState());
  EXPECT_EQ(NextText(broadcaster, *client), "full2");
  EXPECT_EQ(NextText(broadcaster, *client), "d3");
  EXPECT_EQ(NextText(broadcaster, *client), "<nothing>");
}

TEST(EventBroadcasterTest, AClientTooFarBehindIsResyncedAndTheOthersAreNot) {
  EventBroadcaster broadcaster({.max_clients = 4, .max_queued_events = 3});
  auto slow = broadcaster.Connect();
  auto quick = broadcaster.Connect();
  broadcaster.Publish(nullptr, Text("full0"));
  EXPECT_EQ(NextText(broadcaster, *slow), "full0");
  EXPECT_EQ(NextText(broadcaster, *quick), "full0");
  for (int i = 1; i <= 5; ++i) {
    const std::string delta = fmt::format("d{}", i);
    broadcaster.Publish(Text(delta), nullptr);
    EXPECT_EQ(NextText(broadcaster, *quick), delta);
  }
  // The slow client never read: past three queued deltas it lost them and waits for a whole
  // state, which the next round brings.
  EXPECT_TRUE(broadcaster.WantsFullState());
  EXPECT_EQ(broadcaster.counters().resyncs, 1u);
  broadcaster.Publish(Text("d6"), Text("full6"));
  EXPECT_EQ(NextText(broadcaster, *slow), "full6");
  EXPECT_EQ(NextText(broadcaster, *quick), "d6");
  EXPECT_EQ(NextText(broadcaster, *slow), "<nothing>");
}

TEST(EventBroadcasterTest, ClientsAreBoundedAndDisconnectFreesAPlace) {
  EventBroadcaster broadcaster({.max_clients = 2, .max_queued_events = 8});
  auto first = broadcaster.Connect();
  auto second = broadcaster.Connect();
  EXPECT_NE(second, nullptr);
  EXPECT_EQ(broadcaster.Connect(), nullptr);
  EXPECT_EQ(broadcaster.counters().refused, 1u);
  broadcaster.Disconnect(first);
  EXPECT_EQ(NextText(broadcaster, *first), "<closed>");
  EXPECT_NE(broadcaster.Connect(), nullptr);
}

TEST(EventBroadcasterTest, ClosingWakesAWaitingClient) {
  EventBroadcaster broadcaster;
  auto client = broadcaster.Connect();
  std::optional<Event> seen = Text("not yet");
  std::thread waiting([&] { seen = broadcaster.Next(*client, std::chrono::minutes(5)); });
  broadcaster.Close();
  waiting.join();
  EXPECT_FALSE(seen.has_value());
  EXPECT_EQ(broadcaster.Connect(), nullptr) << "no clients once closed";
}

}  // namespace
}  // namespace fleetmap::view
