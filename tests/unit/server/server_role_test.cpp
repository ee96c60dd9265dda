// Which server serves (docs/standby.md): the strongest live one, ties to the lowest id, after a
// start-up's listening; a silent or withdrawn server is gone.
#include "server/server_role.hpp"

#include <gtest/gtest.h>

#include "common/transport/served_state.hpp"

namespace fleetmap::server {
namespace {

using std::chrono::milliseconds;
using SteadyTime = ServerRole::SteadyTime;

const SteadyTime kStart = SteadyTime(std::chrono::hours(1));
const SteadyTime kListened = kStart + transport::kServerSilenceLimit;

transport::FleetServerMessage Server(const std::string& id, int32_t strength) {
  transport::FleetServerMessage server;
  server.server_id = id;
  server.name = "host:" + id;
  server.ownership_strength = strength;
  return server;
}

TEST(ServerRoleTest, ALoneServerServesOnceItHasListened) {
  ServerRole role("b", 100, kStart);
  EXPECT_FALSE(role.Decide(kStart + milliseconds(10)));
  EXPECT_EQ(role.role(), ServerRole::Role::kListening);
  EXPECT_TRUE(role.Decide(kListened));
  EXPECT_TRUE(role.serving());
  EXPECT_FALSE(role.outranked_by().has_value());
}

TEST(ServerRoleTest, AStandbyStandsByWhileAStrongerServerIsHeard) {
  ServerRole standby("a", 50, kStart);
  for (SteadyTime now = kStart; now < kStart + std::chrono::seconds(10); now += milliseconds(500)) {
    standby.Heard(Server("b", 100), now);
    standby.Decide(now);
    ASSERT_FALSE(standby.serving());
  }
  ASSERT_TRUE(standby.outranked_by().has_value());
  EXPECT_EQ(standby.outranked_by()->server_id, "b");
}

TEST(ServerRoleTest, AStandbyServesWhenTheServerFallsSilentAndStandsByWhenItReturns) {
  ServerRole standby("a", 50, kStart);
  standby.Heard(Server("b", 100), kListened);
  EXPECT_TRUE(standby.Decide(kListened));
  EXPECT_EQ(standby.role(), ServerRole::Role::kStandingBy);
  // b is killed: last heard at kListened.
  EXPECT_FALSE(standby.Decide(kListened + transport::kServerSilenceLimit));
  EXPECT_TRUE(standby.Decide(kListened + transport::kServerSilenceLimit + milliseconds(1)));
  EXPECT_TRUE(standby.serving());
  EXPECT_TRUE(standby.peers().empty());
  // b restarted (a new participant, a new id): it outranks the standby again.
  const SteadyTime back = kListened + std::chrono::seconds(20);
  standby.Heard(Server("c", 100), back);
  EXPECT_TRUE(standby.Decide(back));
  EXPECT_FALSE(standby.serving());
}

TEST(ServerRoleTest, AServerThatWithdrewIsGoneAtOnce) {
  ServerRole standby("a", 50, kStart);
  standby.Heard(Server("b", 100), kListened);
  standby.Decide(kListened);
  standby.Withdrew("b");
  EXPECT_TRUE(standby.Decide(kListened + milliseconds(1)));
  EXPECT_TRUE(standby.serving());
}

TEST(ServerRoleTest, AWeakerServerDoesNotTakeTheFleet) {
  ServerRole primary("z", 100, kStart);
  primary.Heard(Server("a", 50), kListened);
  EXPECT_TRUE(primary.Decide(kListened));
  EXPECT_TRUE(primary.serving());
  EXPECT_EQ(primary.peers().size(), 1u);
}

TEST(ServerRoleTest, OfEqualStrengthsTheLowestIdServesAsDdsReadersChoose) {
  ServerRole low("0a", 100, kStart);
  ServerRole high("0b", 100, kStart);
  low.Heard(Server("0b", 100), kListened);
  high.Heard(Server("0a", 100), kListened);
  low.Decide(kListened);
  high.Decide(kListened);
  EXPECT_TRUE(low.serving());
  EXPECT_FALSE(high.serving());
}

TEST(ServerRoleTest, TheStrongestOfSeveralIsTheOneThatServes) {
  ServerRole weakest("a", 10, kStart);
  weakest.Heard(Server("b", 20), kListened);
  weakest.Heard(Server("c", 90), kListened);
  weakest.Heard(Server("d", 90), kListened);
  weakest.Decide(kListened);
  ASSERT_TRUE(weakest.outranked_by().has_value());
  EXPECT_EQ(weakest.outranked_by()->server_id, "c");
}

TEST(ServerRoleTest, ItsOwnSamplesAreNotAPeer) {
  ServerRole role("a", 100, kStart);
  role.Heard(Server("a", 200), kListened);
  role.Decide(kListened);
  EXPECT_TRUE(role.serving());
  EXPECT_TRUE(role.peers().empty());
}

// Shards (docs/shards.md): each shard's servers rank among themselves; a stronger server of
// another shard serves its own region, not this one's.
TEST(ServerRoleTest, AServerOfAnotherShardDoesNotOutrankIt) {
  ServerRole east("b", 50, kStart, "east");
  transport::FleetServerMessage west = Server("a", 100);
  west.shard = "west";
  transport::FleetServerMessage east_standby = Server("c", 10);
  east_standby.shard = "east";
  for (SteadyTime now = kStart; now <= kListened; now += milliseconds(500)) {
    east.Heard(west, now);
    east.Heard(east_standby, now);
    east.Decide(now);
  }
  EXPECT_TRUE(east.serving());
  ASSERT_EQ(east.peers().size(), 1u);
  EXPECT_EQ(east.peers()[0].server_id, "c");
  // An unsharded server ignores shards' servers too.
  ServerRole whole("z", 1, kStart);
  whole.Heard(west, kListened);
  whole.Decide(kListened);
  EXPECT_TRUE(whole.serving());
}

}  // namespace
}  // namespace fleetmap::server
