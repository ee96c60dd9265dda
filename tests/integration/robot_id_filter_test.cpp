// The robot-id content filter over real DDS on loopback (common/transport/internal/
// robot_id_filter.hpp): a reader made for one robot takes that robot's statuses and frames only,
// late-joining for the frames' transient-local history too, while an unfiltered reader on the
// same domain takes every robot's.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>
#include <thread>

#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "tests/integration/loopback_participant.hpp"

namespace fleetmap::transport {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;
using ::testing::UnorderedElementsAre;

constexpr milliseconds kListen{2500};

RobotStatus StatusOf(const std::string& robot, uint32_t sequence) {
  RobotStatus status;
  status.robot = RobotId{robot};
  status.sequence_number = sequence;
  return status;
}

// The robots whose statuses `reader` took while `robots` statuses were written every 100 ms.
std::set<std::string> RobotsHeard(RobotStatusReader& reader, RobotStatusWriter& writer,
                                  const std::vector<std::string>& robots) {
  std::set<std::string> heard;
  const auto until = std::chrono::steady_clock::now() + kListen;
  for (uint32_t sequence = 1; std::chrono::steady_clock::now() < until; ++sequence) {
    for (const std::string& robot : robots)
      EXPECT_TRUE(writer.Write(StatusOf(robot, sequence)).ok());
    std::this_thread::sleep_for(milliseconds(100));
    for (const RobotEvent& event : reader.Drain()) {
      if (event.kind == RobotEvent::Kind::kStatus) heard.insert(event.robot.value);
    }
  }
  return heard;
}

TEST(RobotIdFilterTest, AReaderForOneRobotTakesThatRobotsStatusesOnly) {
  const int domain = process::RandomDomainId();
  auto fleet_side = testing::LoopbackParticipant(domain);
  auto agent_side = testing::LoopbackParticipant(domain);
  auto server_side = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(fleet_side.ok() && agent_side.ok() && server_side.ok());
  auto writer = RobotStatusWriter::Create(**fleet_side);
  ASSERT_TRUE(writer.ok()) << writer.status();
  auto only_alpha = RobotStatusReader::CreateForRobot(**agent_side, RobotId{"alpha"});
  ASSERT_TRUE(only_alpha.ok()) << only_alpha.status();
  auto every_robot = RobotStatusReader::Create(**server_side);
  ASSERT_TRUE(every_robot.ok()) << every_robot.status();

  const std::vector<std::string> robots = {"alpha", "beta", "alphabet", "gamma"};
  EXPECT_THAT(RobotsHeard(**only_alpha, **writer, robots), ElementsAre("alpha"));
  EXPECT_THAT(RobotsHeard(**every_robot, **writer, robots),
              UnorderedElementsAre("alpha", "beta", "alphabet", "gamma"));
}

TEST(RobotIdFilterTest, AFrameReaderForOneRobotTakesOnlyItsFrameFromTheHistoryToo) {
  const int domain = process::RandomDomainId();
  auto server_side = testing::LoopbackParticipant(domain);
  auto agent_side = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(server_side.ok() && agent_side.ok());
  auto writer = RobotFrameWriter::Create(**server_side);
  ASSERT_TRUE(writer.ok()) << writer.status();
  // Written before the agent's reader exists: it reads them from the writer's history.
  for (const std::string robot : {"alpha", "beta", "gamma"}) {
    RobotFrame frame;
    frame.robot = RobotId{robot};
    frame.state = RobotFrame::State::kPlaced;
    frame.fleet_from_map = Pose2{robot == "beta" ? 2.0 : 1.0, 0.0, 0.0};
    ASSERT_TRUE((*writer)->Write(frame).ok());
  }
  auto reader = RobotFrameReader::CreateForRobot(**agent_side, RobotId{"beta"});
  ASSERT_TRUE(reader.ok()) << reader.status();
  std::vector<std::string> frames;
  const auto until = std::chrono::steady_clock::now() + kListen;
  while (std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(milliseconds(100));
    for (const RobotFrameEvent& event : (*reader)->Drain()) {
      if (event.kind != RobotFrameEvent::Kind::kSample) continue;
      frames.push_back(event.message.robot.value);
      EXPECT_EQ(event.message.fleet_from_map.x, 2.0);
    }
  }
  EXPECT_THAT(frames, ElementsAre("beta"));
}

TEST(RobotIdFilterTest, TopicsNotKeyedByARobotIdFirstRefuseTheFilter) {
  auto participant = testing::LoopbackParticipant(process::RandomDomainId());
  ASSERT_TRUE(participant.ok());
  const auto reader = EntityReader::CreateForRobot(**participant, RobotId{"alpha"});
  ASSERT_FALSE(reader.ok());
  EXPECT_EQ(reader.status().code(), StatusCode::kInternal);
}

}  // namespace
}  // namespace fleetmap::transport
