// A peer that speaks the wire types but sends nonsense: the server drops each bad sample with a
// message naming the robot and the problem, and keeps serving the others.

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <gtest/gtest.h>

#include "common/transport/endpoint.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/qos.hpp"
#include "common/transport/topics.hpp"
#include "fleetmap_msgs/msg/RobotStatusPubSubTypes.h"
#include "nav_msgs/msg/OccupancyGridPubSubTypes.h"
#include "tests/support/subprocess.hpp"

namespace fleetmap {
namespace {

namespace dds = eprosima::fastdds::dds;
using std::chrono::seconds;

const std::string kAgent = std::string(FLEETMAP_BINARY_DIR) + "/robot_agent/fleetmap-agent";
const std::string kServer = std::string(FLEETMAP_BINARY_DIR) + "/server/fleetmap-server";
const std::string kMap = std::string(FLEETMAP_SHARED_MAPS_DIR) + "/tb3_world.yaml";
constexpr seconds kDeadline{20};

fleetmap_msgs::msg::dds_::RobotStatus_ StatusOf(const std::string& robot) {
  fleetmap_msgs::msg::dds_::RobotStatus_ status;
  status.robot_id(robot);
  status.map_from_robot().theta(0.0);
  return status;
}

nav_msgs::msg::dds_::OccupancyGrid_ Grid(uint32_t width, uint32_t height, size_t cells) {
  nav_msgs::msg::dds_::OccupancyGrid_ grid;
  grid.info().width(width);
  grid.info().height(height);
  grid.info().resolution(0.05f);
  grid.info().origin().orientation().w(1.0);
  grid.data(std::vector<int8_t>(cells, 0));
  return grid;
}

TEST(MalformedSamplesTest, ServerDropsBadSamplesAndKeepsServing) {
  const int domain = testing::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  testing::Subprocess server({kServer, "--duration", "60"}, env);
  testing::Subprocess alpha({kAgent, "--robot-id", "alpha", "--map", kMap}, env);
  ASSERT_TRUE(server.WaitForOutput("map from alpha", kDeadline)) << server.Output();

  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  auto participant = transport::Participant::Create(options);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto status_writer = transport::WriterEndpoint::Create(
      **participant, transport::kRobotStatusTopic,
      dds::TypeSupport(new fleetmap_msgs::msg::dds_::RobotStatus_PubSubType()),
      transport::RobotStatusQos().writer);
  ASSERT_TRUE(status_writer.ok()) << status_writer.status();
  auto map_writer = transport::WriterEndpoint::Create(
      **participant, transport::RobotMapTopic(RobotId{"gamma"}),
      dds::TypeSupport(new nav_msgs::msg::dds_::OccupancyGrid_PubSubType()),
      transport::OccupancyGridQos().writer);
  ASSERT_TRUE(map_writer.ok()) << map_writer.status();

  // A robot name that is not a ROS name token.
  auto bad_name = StatusOf("bad/robot");
  ASSERT_TRUE((*status_writer)->writer()->write(&bad_name));
  EXPECT_TRUE(server.WaitForOutput("dropped a robot status sample", kDeadline))
      << server.Output();
  EXPECT_NE(server.Output().find("bad/robot"), std::string::npos);

  // A valid robot whose map says 10 x 10 but carries 5 cells.
  auto gamma = StatusOf("gamma");
  ASSERT_TRUE((*status_writer)->writer()->write(&gamma));
  ASSERT_TRUE(server.WaitForOutput("robot gamma joined", kDeadline)) << server.Output();
  auto short_grid = Grid(10, 10, 5);
  ASSERT_TRUE((*map_writer)->writer()->write(&short_grid));
  EXPECT_TRUE(server.WaitForOutput("dropped a map from gamma", kDeadline)) << server.Output();
  EXPECT_NE(server.Output().find("10 x 10 cells but carries 5"), std::string::npos);

  // The same peer then sends a good map: it is taken, and alpha was never disturbed.
  auto good_grid = Grid(2, 3, 6);
  ASSERT_TRUE((*map_writer)->writer()->write(&good_grid));
  EXPECT_TRUE(server.WaitForOutput("map from gamma: 2 x 3 cells", kDeadline)) << server.Output();

  map_writer->reset();
  status_writer->reset();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("alpha            active"), std::string::npos) << server.Output();
}

}  // namespace
}  // namespace fleetmap
