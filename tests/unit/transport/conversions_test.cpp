#include "common/transport/internal/conversions.hpp"
#include "common/transport/participant.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

namespace fleetmap::transport {
namespace {

MapMessage SmallMap() {
  MapMessage message;
  message.grid = grid::OccupancyGrid(3, 2, 0.05, Pose2{-1.5, 2.25, std::numbers::pi / 2});
  message.grid.at(0, 0) = grid::kOccupiedValue;
  message.grid.at(2, 1) = grid::kFreeValue;
  message.grid.at(1, 1) = 42;
  message.frame_id = "alpha/map";
  message.stamp = Timestamp(std::chrono::seconds(1700000000) + std::chrono::nanoseconds(123456789));
  return message;
}

TEST(ConversionsTest, OccupancyGridRoundTripsAsRos2LaysItOut) {
  const MapMessage original = SmallMap();
  const auto idl = ToIdl(original);
  EXPECT_EQ(idl.info().width(), 3u);
  EXPECT_EQ(idl.info().height(), 2u);
  EXPECT_EQ(idl.header().frame_id(), "alpha/map");
  EXPECT_EQ(idl.header().stamp().sec(), 1700000000);
  EXPECT_EQ(idl.header().stamp().nanosec(), 123456789u);
  // Row-major from the origin: cell (x, y) at y * width + x.
  EXPECT_EQ(idl.data()[0], 100);
  EXPECT_EQ(idl.data()[1 * 3 + 2], 0);
  EXPECT_NEAR(idl.info().origin().orientation().z(), std::sin(std::numbers::pi / 4), 1e-12);

  const auto back = FromIdl(idl);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->grid.data(), original.grid.data());
  EXPECT_FLOAT_EQ(back->grid.resolution(), 0.05);
  EXPECT_NEAR(back->grid.origin().yaw, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(back->stamp, original.stamp);
}

TEST(ConversionsTest, RejectsCellCountMismatch) {
  auto idl = ToIdl(SmallMap());
  idl.data().pop_back();
  const auto back = FromIdl(idl);
  ASSERT_FALSE(back.ok());
  EXPECT_EQ(back.status().message(), "OccupancyGrid says 3 x 2 cells but carries 5");
}

TEST(ConversionsTest, RejectsOverflowingDimensions) {
  auto idl = ToIdl(SmallMap());
  idl.info().width(0x10000);
  idl.info().height(0x10000);  // 2^32 cells would wrap a 32-bit product to 0
  idl.data().clear();
  EXPECT_FALSE(FromIdl(idl).ok());
}

TEST(ConversionsTest, RejectsBadResolutionOriginAndValues) {
  auto bad_resolution = ToIdl(SmallMap());
  bad_resolution.info().resolution(std::numeric_limits<float>::quiet_NaN());
  EXPECT_NE(FromIdl(bad_resolution).status().message().find("resolution"), std::string::npos);

  auto zero_resolution = ToIdl(SmallMap());
  zero_resolution.info().resolution(0.0f);
  EXPECT_FALSE(FromIdl(zero_resolution).ok());

  auto tilted = ToIdl(SmallMap());
  tilted.info().origin().orientation().x(0.7071);
  tilted.info().origin().orientation().w(0.7071);
  tilted.info().origin().orientation().z(0.0);
  EXPECT_NE(FromIdl(tilted).status().message().find("origin"), std::string::npos);

  auto out_of_range = ToIdl(SmallMap());
  out_of_range.data()[2] = 101;
  out_of_range.data()[3] = -2;
  EXPECT_EQ(FromIdl(out_of_range).status().message(), "OccupancyGrid has 2 cells outside -1..100");
}

TEST(ConversionsTest, RobotStatusRoundTripsAndValidatesName) {
  RobotStatus status;
  status.robot = RobotId{"alpha"};
  status.fleet_from_map = Pose2{1.0, 2.0, 0.5};
  status.map_from_robot = Pose2{-3.0, 4.0, -1.0};
  status.map_topic = "rt/alpha/map";
  status.map_width = 10;
  status.maps_published = 3;
  status.bytes_published = 1ull << 40;
  status.sequence_number = 7;
  status.tiles_in_map_frame = true;
  const auto back = FromIdl(ToIdl(status));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->robot, status.robot);
  EXPECT_EQ(back->fleet_from_map, status.fleet_from_map);
  EXPECT_EQ(back->map_from_robot, status.map_from_robot);
  EXPECT_EQ(back->bytes_published, status.bytes_published);
  EXPECT_EQ(back->sequence_number, 7u);
  EXPECT_TRUE(back->tiles_in_map_frame);

  auto bad = ToIdl(status);
  bad.robot_id("../etc");
  EXPECT_FALSE(FromIdl(bad).ok());
  auto nan_pose = ToIdl(status);
  nan_pose.fleet_from_map().x(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(FromIdl(nan_pose).ok());
}

TEST(MapUpdateTest, AppliesInsideTheMapAndRefusesTheRest) {
  grid::OccupancyGrid map(4, 3, 0.1, Pose2{}, grid::kUnknownValue);
  const MapUpdate update{
      .x = 1, .y = 1, .width = 3, .height = 2, .data = {0, 0, 100, 0, 100, 0}, .stamp = {}};
  ASSERT_TRUE(ApplyMapUpdate(update, &map).ok());
  EXPECT_EQ(map.at(3, 1), 100);
  EXPECT_EQ(map.at(2, 2), 100);
  EXPECT_EQ(map.at(0, 0), grid::kUnknownValue);
  const grid::OccupancyGrid before = map;
  const MapUpdate too_wide{.x = 2, .y = 0, .width = 3, .height = 1, .data = {0, 0, 0}, .stamp = {}};
  EXPECT_NE(ApplyMapUpdate(too_wide, &map).message().find("outside the 4 x 3 map"),
            std::string::npos);
  EXPECT_EQ(map, before);
  const MapUpdate negative{.x = -1, .y = 0, .width = 1, .height = 1, .data = {0}, .stamp = {}};
  EXPECT_FALSE(ApplyMapUpdate(negative, &map).ok());
}

TEST(MapUpdateTest, FromIdlChecksCountsAndValues) {
  const MapUpdate update{.x = 1, .y = 2, .width = 2, .height = 1, .data = {0, 100}, .stamp = {}};
  auto idl = ToIdl(update);
  const auto back = FromIdl(idl);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->data, update.data);
  idl.data().push_back(0);
  EXPECT_NE(FromIdl(idl).status().message().find("2 x 1 cells but carries 3"), std::string::npos);
  idl.data({0, 120});
  EXPECT_FALSE(FromIdl(idl).ok());
}

TEST(ParticipantOptionsTest, DomainComesFromOptionThenEnvironment) {
  EXPECT_EQ(*ResolveDomainId(7), 7);
  EXPECT_FALSE(ResolveDomainId(233).ok());
  EXPECT_FALSE(ResolveDomainId(-1).ok());
  setenv("FLEETMAP_DOMAIN", "12", 1);
  EXPECT_EQ(*ResolveDomainId(std::nullopt), 12);
  setenv("FLEETMAP_DOMAIN", "twelve", 1);
  EXPECT_NE(ResolveDomainId(std::nullopt).status().message().find("twelve"), std::string::npos);
  unsetenv("FLEETMAP_DOMAIN");
  EXPECT_EQ(*ResolveDomainId(std::nullopt), 0);
}

TEST(ParticipantOptionsTest, DiscoveryServersComeFromOptionThenEnvironment) {
  unsetenv("ROS_DISCOVERY_SERVER");
  EXPECT_EQ(*ResolveDiscoveryServer(std::nullopt), "") << "simple discovery";
  EXPECT_EQ(*ResolveDiscoveryServer("127.0.0.1:11811"), "127.0.0.1:11811");
  EXPECT_EQ(*ResolveDiscoveryServer("10.0.0.1:11811;10.0.0.2:11812"),
            "10.0.0.1:11811;10.0.0.2:11812");
  const Status bad = ResolveDiscoveryServer("127.0.0.1:port").status();
  EXPECT_EQ(bad.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(bad.message().find("--discovery-server \"127.0.0.1:port\""), std::string::npos)
      << bad.message();
  setenv("ROS_DISCOVERY_SERVER", "192.168.1.2:11811", 1);
  EXPECT_EQ(*ResolveDiscoveryServer(std::nullopt), "192.168.1.2:11811");
  EXPECT_EQ(*ResolveDiscoveryServer(""), "") << "the option overrides the environment";
  setenv("ROS_DISCOVERY_SERVER", "nonsense:", 1);
  EXPECT_NE(ResolveDiscoveryServer(std::nullopt).status().message().find("ROS_DISCOVERY_SERVER"),
            std::string::npos);
  unsetenv("ROS_DISCOVERY_SERVER");
}

}  // namespace
}  // namespace fleetmap::transport
