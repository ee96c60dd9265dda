// The agent's status heartbeat over real DDS on loopback: statuses keep the robot alive while the
// agent's loop is busy, and stop, so that the robot is reported lost, once the loop has hung.

#include "robot_agent/status_heartbeat.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "common/core/wake_up.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "tests/integration/loopback_participant.hpp"

namespace fleetmap::agent {
namespace {

using std::chrono::milliseconds;

TEST(StatusHeartbeatTest, ABusyLoopKeepsTheRobotAliveAndAHungOneLosesIt) {
  const int domain = process::RandomDomainId();
  auto robot_side = testing::LoopbackParticipant(domain);
  auto server_side = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(robot_side.ok() && server_side.ok());
  auto writer = transport::RobotStatusWriter::Create(**robot_side);
  ASSERT_TRUE(writer.ok()) << writer.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RobotStatusReader::Create(**server_side, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  RobotStatus status;
  status.robot = RobotId{"alpha"};
  status.map_revision = 7;
  // Statuses every 100 ms; a loop silent for 1.5 s has hung.
  StatusHeartbeat heartbeat(**writer, milliseconds(100), milliseconds(1500));
  ASSERT_TRUE(heartbeat.Start(status).ok());

  // The loop is busy for 1 s (no Update): the statuses go on, numbered, saying what it said.
  std::vector<transport::RobotEvent> events;
  const auto collect = [&](milliseconds how_long) {
    const auto until = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < until) {
      wake_up->WaitFor(milliseconds(50));
      for (transport::RobotEvent& event : (*reader)->Drain()) events.push_back(std::move(event));
    }
  };
  collect(milliseconds(1000));
  size_t statuses = 0;
  uint32_t last_sequence = 0;
  for (const transport::RobotEvent& event : events) {
    ASSERT_NE(event.kind, transport::RobotEvent::Kind::kLost);
    if (event.kind != transport::RobotEvent::Kind::kStatus) continue;
    ++statuses;
    EXPECT_EQ(event.status.map_revision, 7u);
    EXPECT_GT(event.status.sequence_number, last_sequence);
    last_sequence = event.status.sequence_number;
  }
  EXPECT_GE(statuses, 5u);  // about 10 in 1 s

  // The loop hangs: past 1.5 s the statuses stop and the 2 s lease lapses.
  events.clear();
  collect(milliseconds(5000));
  bool lost = false;
  for (const transport::RobotEvent& event : events) {
    lost =
        lost || (event.kind == transport::RobotEvent::Kind::kLost && event.robot.value == "alpha");
  }
  EXPECT_TRUE(lost);
  heartbeat.Stop();
}

}  // namespace
}  // namespace fleetmap::agent
