// Fleets on adjacent DDS domains must never meet with localhost-only discovery (issue 15): the
// unicast peer list of domain D once reached the discovery ports of domain D + 1, so a server on
// D fused the agents of D + 1 and the other way round. Readers and writers in this process (wire
// delivery, no intra-process shortcut) and real server and agent processes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <utility>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;

// Bounds the waits on a loaded CI machine; not an assertion on time.
constexpr seconds kDeadline{20};
// How long to keep listening for the other domain once this domain's peers have met: longer than
// two participant announcement periods (1.5 s each), and the initial burst comes at start.
constexpr seconds kSettle{4};

// Two neighbouring domains (D, D + 1), both claimed so that no parallel test uses them.
std::pair<int, int> ClaimAdjacentDomains() {
  for (int attempt = 0; attempt < 50; ++attempt) {
    const int domain = process::RandomDomainId();
    if (domain < 232 && process::ClaimDomainId(domain + 1)) return {domain, domain + 1};
  }
  ADD_FAILURE() << "no free pair of adjacent DDS domains";
  return {1, 2};
}

std::unique_ptr<transport::Participant> MakeParticipant(int domain) {
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  auto participant = transport::Participant::Create(options);
  EXPECT_TRUE(participant.ok()) << participant.status();
  return participant.ok() ? std::move(participant).value() : nullptr;
}

// One domain's side: a participant with a status writer speaking for `robot` and a status reader
// that records every robot it hears of.
struct DomainSide {
  int domain = 0;
  std::string robot;
  std::unique_ptr<transport::Participant> participant;
  std::unique_ptr<transport::RobotStatusWriter> writer;
  std::shared_ptr<WakeUp> wake_up = std::make_shared<WakeUp>();
  std::unique_ptr<transport::RobotStatusReader> reader;
  std::set<std::string> heard;

  ~DomainSide() {
    reader.reset();
    writer.reset();
  }

  void Create(int domain_id, std::string robot_id) {
    domain = domain_id;
    robot = std::move(robot_id);
    participant = MakeParticipant(domain);
    ASSERT_NE(participant, nullptr);
    auto status_writer = transport::RobotStatusWriter::Create(*participant);
    ASSERT_TRUE(status_writer.ok()) << status_writer.status();
    writer = std::move(status_writer).value();
    auto status_reader = transport::RobotStatusReader::Create(*participant, wake_up);
    ASSERT_TRUE(status_reader.ok()) << status_reader.status();
    reader = std::move(status_reader).value();
  }

  void WriteStatus() {
    RobotStatus status;
    status.robot = RobotId{robot};
    ASSERT_TRUE(writer->Write(status).ok());
  }

  void Listen(milliseconds timeout) {
    wake_up->WaitFor(timeout);
    for (const transport::RobotEvent& event : reader->Drain()) heard.insert(event.robot.value);
  }
};

TEST(DomainIsolationTest, LocalhostOnlyEndpointsOnAdjacentDomainsNeverMatch) {
  const auto [domain, next_domain] = ClaimAdjacentDomains();
  // Both directions: D's peer list must not reach D + 1, and D + 1's must not reach D (a match
  // found from either side would join both).
  DomainSide low, high;
  ASSERT_NO_FATAL_FAILURE(low.Create(domain, "robot_on_low"));
  ASSERT_NO_FATAL_FAILURE(high.Create(next_domain, "robot_on_high"));

  // Each side hears its own robot: the endpoints work, so silence about the other is meaningful.
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < deadline &&
         (!low.heard.contains(low.robot) || !high.heard.contains(high.robot))) {
    low.WriteStatus();  // statuses keep the writers' liveliness, as an agent's do
    high.WriteStatus();
    low.Listen(milliseconds(100));
    high.Listen(milliseconds(100));
  }
  ASSERT_TRUE(low.heard.contains(low.robot)) << "domain " << domain;
  ASSERT_TRUE(high.heard.contains(high.robot)) << "domain " << next_domain;

  const auto settled = std::chrono::steady_clock::now() + kSettle;
  while (std::chrono::steady_clock::now() < settled) {
    low.WriteStatus();
    high.WriteStatus();
    low.Listen(milliseconds(100));
    high.Listen(milliseconds(100));
  }
  EXPECT_EQ(low.heard, std::set<std::string>{low.robot}) << "domain " << domain;
  EXPECT_EQ(high.heard, std::set<std::string>{high.robot}) << "domain " << next_domain;
}

TEST(DomainIsolationTest, ServersFuseOnlyTheAgentsOfTheirOwnDomain) {
  const auto [domain, next_domain] = ClaimAdjacentDomains();
  grid::OccupancyGrid grid(100, 100, 0.05, Pose2{}, grid::kFreeValue);
  for (int i = 0; i < 100; ++i) grid.at(i, 50) = grid::kOccupiedValue;
  const std::string map_path = ::testing::TempDir() + "/domain_isolation_" +
                               std::to_string(getpid()) + "_" + std::to_string(domain) + ".yaml";
  ASSERT_TRUE(grid::SaveMap(grid, map_path).ok());

  const auto env = [](int d) {
    return std::map<std::string, std::string>{{"FLEETMAP_DOMAIN", std::to_string(d)},
                                              {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  };
  const auto agent = [&](const std::string& robot, int d) {
    return std::make_unique<Subprocess>(
        std::vector<std::string>{testing::kAgentBinary, "--robot-id", robot, "--map", map_path},
        env(d));
  };
  Subprocess low_server({testing::kServerBinary, "--duration", "60"}, env(domain));
  Subprocess high_server({testing::kServerBinary, "--duration", "60"}, env(next_domain));
  auto low_agent = agent("low_robot", domain);
  auto high_agent = agent("high_robot", next_domain);

  ASSERT_TRUE(low_server.WaitForOutput("robot low_robot joined", kDeadline)) << low_server.Output();
  ASSERT_TRUE(high_server.WaitForOutput("robot high_robot joined", kDeadline))
      << high_server.Output();
  std::this_thread::sleep_for(kSettle);
  EXPECT_EQ(low_server.Output().find("high_robot"), std::string::npos) << low_server.Output();
  EXPECT_EQ(high_server.Output().find("low_robot"), std::string::npos) << high_server.Output();
  std::remove(map_path.c_str());
}

}  // namespace
}  // namespace fleetmap
