// An agent tells its operator when it sees no fleet server (wrong domain, server down, a secured
// fleet it is not part of), and when it sees one again: real agent and server processes.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <map>
#include <string>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using process::Subprocess;
using std::chrono::seconds;
// A killed server is noticed once its participant's lease (6 s) runs out.
constexpr seconds kDeadline{25};

const std::string kMap = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/trinary_4x3.yaml";

TEST(AgentServerWatchTest, AnAgentSaysWhenNoServerIsInSightAndWhenOneComesAndGoes) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  Subprocess agent(
      {testing::kAgentBinary, "--robot-id", "alpha", "--map", kMap, "--server-wait", "1"}, env);
  ASSERT_TRUE(agent.WaitForOutput("no fleet server seen for 1 s", kDeadline)) << agent.Output();

  Subprocess server({testing::kServerBinary, "--duration", "60"}, env);
  ASSERT_TRUE(server.WaitForOutput("robot alpha joined", kDeadline)) << server.Output();
  EXPECT_TRUE(agent.WaitForOutput("a fleet server is seen now", kDeadline)) << agent.Output();

  server.Signal(SIGKILL);
  server.Wait(kDeadline);
  EXPECT_TRUE(agent.WaitForOutput("the fleet server has been gone for 1 s", kDeadline))
      << agent.Output();
  agent.Signal(SIGINT);
  EXPECT_EQ(agent.Wait(kDeadline), 0) << agent.Output();
}

}  // namespace
}  // namespace fleetmap
