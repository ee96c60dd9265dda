// Issue 31, item 1: a robot whose frame is given at any yaw is fused at that transform on every
// wire. The agent cuts its tiles (or patches) in its own map frame and the server carries them
// into the fleet frame at the given fleet_from_map, the path a placement by registration takes.
// Robots at 30, 90, 180 and -135 degrees on the tile wire, and on the grid and patch wires, each
// far from the others, all in one real server; the fused map must hold each map where its
// transform puts it. Bad transforms are refused, named, exit 2.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/loopback_participant.hpp"
#include "tests/integration/map_agreement.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr seconds kDeadline{60};  // bounds waits on a loaded machine; not an assertion

struct GivenRobot {
  std::string id;
  double yaw_deg;
  std::string wire;
  Pose2 fleet_from_map;
};

class GivenFrameTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto house =
        grid::LoadMap(std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml");
    ASSERT_TRUE(house.ok()) << house.status();
    house_ = house->grid;
    house_path_ = ::testing::TempDir() + "/given_frame_" + std::to_string(getpid()) + ".yaml";
    ASSERT_TRUE(grid::SaveMap(house_, house_path_).ok());
    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  }

  grid::OccupancyGrid house_;
  std::string house_path_;
  int domain_ = 0;
  std::map<std::string, std::string> env_;
};

TEST_F(GivenFrameTest, RobotsGivenRotatedFramesAreFusedWhereTheirTransformsPutThemOnEveryWire) {
  // 40 m apart along x: no two overlap, all fit one fused grid.
  std::vector<GivenRobot> robots = {
      {"turned30", 30.0, "tiles", {}},   {"turned90", 90.0, "tiles", {}},
      {"turned180", 180.0, "tiles", {}}, {"turnedm135", -135.0, "tiles", {}},
      {"gridwire", 30.0, "grid", {}},    {"patchwire", -135.0, "grid-updates-zstd", {}}};
  Subprocess server({testing::kServerBinary, "--duration", "120", "--no-object-learning",
                     "--no-extrapolation", "--map-period", "0.5"},
                    env_);
  std::vector<std::unique_ptr<Subprocess>> agents;
  for (size_t i = 0; i < robots.size(); ++i) {
    GivenRobot& robot = robots[i];
    robot.fleet_from_map =
        Pose2{40.0 * static_cast<double>(i) + 20.0, 20.0, robot.yaw_deg * M_PI / 180.0};
    agents.push_back(std::make_unique<Subprocess>(
        std::vector<std::string>{
            testing::kAgentBinary, "--robot-id", robot.id, "--map", house_path_, "--wire",
            robot.wire, "--fleet-from-map", std::to_string(robot.fleet_from_map.x),
            std::to_string(robot.fleet_from_map.y), std::to_string(robot.fleet_from_map.yaw)},
        env_));
  }

  auto participant = testing::LoopbackParticipant(domain_);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto maps =
      transport::OccupancyGridReader::Create(**participant, transport::kFleetMapTopic, wake_up);
  ASSERT_TRUE(maps.ok()) << maps.status();
  auto frames = transport::RobotFrameReader::Create(**participant, wake_up);
  ASSERT_TRUE(frames.ok()) << frames.status();

  std::map<std::string, double> agreement;
  std::map<std::string, transport::RobotFrameMessage> frame_of;
  const auto all_agree = [&] {
    for (const GivenRobot& robot : robots) {
      if (agreement[robot.id] < 0.95) return false;
    }
    return true;
  };
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < deadline && !all_agree()) {
    wake_up->WaitFor(milliseconds(200));
    for (transport::RobotFrameEvent& event : (*frames)->Drain()) {
      if (event.kind == transport::RobotFrameEvent::Kind::kSample) {
        frame_of[event.message.robot.value] = event.message;
      }
    }
    for (StatusOr<transport::MapMessage>& map : (*maps)->Drain()) {
      if (!map.ok()) continue;
      for (const GivenRobot& robot : robots) {
        agreement[robot.id] =
            testing::Agreement(house_, robot.fleet_from_map.ToTransform(), map->grid);
      }
    }
  }
  for (const GivenRobot& robot : robots) {
    SCOPED_TRACE(robot.id + " on " + robot.wire);
    EXPECT_GE(agreement[robot.id], 0.95) << server.Output();
    ASSERT_EQ(frame_of.count(robot.id), 1u) << server.Output();
    const transport::RobotFrameMessage& frame = frame_of.at(robot.id);
    EXPECT_EQ(frame.state, transport::RobotFrameMessage::State::kGiven);
    EXPECT_NEAR(frame.fleet_from_map.x, robot.fleet_from_map.x, 1e-6);
    EXPECT_NEAR(NormalizeAngle(frame.fleet_from_map.yaw - robot.fleet_from_map.yaw), 0.0, 1e-6);
  }
  EXPECT_EQ(server.Output().find("rotated maps are not supported"), std::string::npos);
  server.Signal(SIGINT);
  EXPECT_EQ(server.Wait(seconds(30)), 0);
}

TEST_F(GivenFrameTest, ANonFiniteYawIsRefusedNamedWithExitTwo) {
  Subprocess agent({testing::kAgentBinary, "--robot-id", "alpha", "--map", house_path_,
                    "--fleet-from-map", "0", "0", "nan"},
                   env_);
  EXPECT_EQ(agent.Wait(seconds(30)), 2) << agent.Output();
  EXPECT_NE(agent.Output().find("--fleet-from-map is not finite"), std::string::npos)
      << agent.Output();
}

}  // namespace
}  // namespace fleetmap
