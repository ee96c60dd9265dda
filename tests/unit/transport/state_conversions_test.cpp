#include "common/transport/internal/state_conversions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fleetmap::transport {
namespace {

EntityMessage Door() {
  scene::DoorEntity door;
  door.id = "door_3";
  door.hinge = {1.0, 2.0};
  door.latch = {1.9, 2.0};
  door.opening_direction = {0.0, 1.0};
  door.open = false;
  EntityMessage message;
  message.robot = RobotId{"alpha"};
  message.entity = door;
  return message;
}

EntityMessage Person() {
  scene::PersonTrack track;
  track.id = "person_1";
  track.points = {{0.0, {1.0, 1.0}, 0.0}, {0.5, {1.5, 1.0}, 0.1}};
  track.dominant_side = -1;
  track.left_view = true;
  EntityMessage message;
  message.robot = RobotId{"beta"};
  message.entity = track;
  return message;
}

TEST(StateConversionsTest, DoorRoundTrips) {
  StatusOr<fleetmap_msgs::msg::dds_::Entity_> sample = ToIdl(Door());
  ASSERT_TRUE(sample.ok()) << sample.status();
  EXPECT_EQ(sample->entity_class(), kEntityDoor);
  StatusOr<EntityMessage> back = FromIdl(*sample);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->robot.value, "alpha");
  EXPECT_EQ(back->entity_id(), "door_3");
  const auto* door = std::get_if<scene::DoorEntity>(&back->entity);
  ASSERT_NE(door, nullptr);
  EXPECT_NEAR(door->width(), 0.9, 1e-12);
  EXPECT_NEAR(door->opening_direction.y(), 1.0, 1e-12);
  EXPECT_FALSE(door->open);
}

TEST(StateConversionsTest, StairsRoundTripAndRefuseANegativeRun) {
  scene::StairsEntity stairs;
  stairs.id = "stairs_1";
  stairs.position = {4.0, -1.0};
  stairs.ascending = {-1.0, 0.0};
  stairs.step_width = 1.2;
  stairs.next_floor_height = 2.8;
  stairs.run_length = 3.5;
  EntityMessage message;
  message.robot = RobotId{"gamma"};
  message.entity = stairs;
  auto sample = *ToIdl(message);
  StatusOr<EntityMessage> back = FromIdl(sample);
  ASSERT_TRUE(back.ok()) << back.status();
  const auto* got = std::get_if<scene::StairsEntity>(&back->entity);
  ASSERT_NE(got, nullptr);
  EXPECT_NEAR(got->ascending.x(), -1.0, 1e-12);
  EXPECT_DOUBLE_EQ(got->run_length, 3.5);
  EXPECT_DOUBLE_EQ(got->next_floor_height, 2.8);
  sample.run_length(-1.0);
  EXPECT_FALSE(FromIdl(sample).ok());
  sample.run_length(1.0);
  sample.step_width(0.0);
  EXPECT_FALSE(FromIdl(sample).ok());
}

TEST(StateConversionsTest, PersonTrackRoundTrips) {
  StatusOr<EntityMessage> back = FromIdl(*ToIdl(Person()));
  ASSERT_TRUE(back.ok()) << back.status();
  const auto* track = std::get_if<scene::PersonTrack>(&back->entity);
  ASSERT_NE(track, nullptr);
  ASSERT_EQ(track->points.size(), 2u);
  EXPECT_DOUBLE_EQ(track->points[1].position.x(), 1.5);
  EXPECT_DOUBLE_EQ(track->points[1].heading, 0.1);
  EXPECT_EQ(track->dominant_side, -1);
  EXPECT_TRUE(track->left_view);
  EXPECT_FALSE(track->entered_view);
}

TEST(StateConversionsTest, RefusesBrokenEntities) {
  auto zero_width = *ToIdl(Door());
  zero_width.x({1.0, 1.0});
  zero_width.y({2.0, 2.0});
  StatusOr<EntityMessage> refused = FromIdl(zero_width);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("zero width"), std::string::npos);
  EXPECT_NE(refused.status().message().find("door_3"), std::string::npos);

  auto not_finite = *ToIdl(Door());
  not_finite.x({std::numeric_limits<double>::quiet_NaN(), 1.0});
  EXPECT_FALSE(FromIdl(not_finite).ok());

  auto unknown_class = *ToIdl(Door());
  unknown_class.entity_class(9);
  refused = FromIdl(unknown_class);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("unknown entity class 9"), std::string::npos);

  auto bad_robot = *ToIdl(Door());
  bad_robot.robot_id("no spaces allowed");
  EXPECT_FALSE(FromIdl(bad_robot).ok());

  auto short_track = *ToIdl(Person());
  short_track.track_stamps({0.0});
  EXPECT_FALSE(FromIdl(short_track).ok());

  auto backwards = *ToIdl(Person());
  backwards.track_stamps({1.0, 0.0});
  EXPECT_FALSE(FromIdl(backwards).ok());
}

TEST(StateConversionsTest, SubmapRoundTripsWithEdgesAndCells) {
  SubmapMessage message;
  message.submap.id = 4;
  message.submap.kind = scene::SubmapKind::kPredictedDoor;
  message.submap.place = 2;
  message.submap.elevation = 2.75;
  message.submap.map_from_submap = {3.0, 1.0, 0.5};
  message.submap.navigable = grid::OccupancyGrid(3, 2, 0.1, Pose2{-0.15, -0.1, 0.0});
  message.submap.navigable.at(1, 1) = 0;
  message.state = scene::SubmapState::kConfirmed;
  message.precision = 0.97F;
  message.observed_fraction = 0.6F;
  message.source_robot = RobotId{"alpha"};
  message.source_entity = "door_3";
  message.edges.push_back({4, 0, Pose2{-1.0, 2.0, -0.5}, "door_3"});
  StatusOr<SubmapMessage> back = FromIdl(*ToIdl(message));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->submap.id, 4u);
  EXPECT_EQ(back->submap.kind, scene::SubmapKind::kPredictedDoor);
  EXPECT_EQ(back->state, scene::SubmapState::kConfirmed);
  EXPECT_DOUBLE_EQ(back->submap.elevation, 2.75);
  EXPECT_EQ(back->submap.navigable.width(), 3);
  EXPECT_EQ(back->submap.navigable.at(1, 1), 0);
  EXPECT_EQ(back->submap.navigable.at(0, 0), grid::kUnknownValue);
  EXPECT_NEAR(back->submap.navigable.resolution(), 0.1, 1e-7);
  ASSERT_EQ(back->edges.size(), 1u);
  EXPECT_EQ(back->edges[0].to, 0u);
  EXPECT_DOUBLE_EQ(back->edges[0].from_T_to.y, 2.0);
  EXPECT_EQ(back->edges[0].entity_id, "door_3");
  EXPECT_FLOAT_EQ(back->precision, 0.97F);
}

TEST(StateConversionsTest, RefusesSubmapsWhoseCountsDisagree) {
  SubmapMessage message;
  message.submap.navigable = grid::OccupancyGrid(2, 2, 0.05);
  auto sample = *ToIdl(message);
  sample.width(1000);
  StatusOr<SubmapMessage> refused = FromIdl(sample);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("4 values"), std::string::npos);

  sample = *ToIdl(message);
  sample.edge_to({1, 2});
  EXPECT_FALSE(FromIdl(sample).ok());

  sample = *ToIdl(message);
  sample.state(17);
  EXPECT_FALSE(FromIdl(sample).ok());
}

// Found by fuzz/cdr_samples_fuzzer.cpp: a side above INT32_MAX with the other side 0 holds no
// cells, so the counts agreed, and the grid's constructor stopped the process on a negative width.
TEST(StateConversionsTest, RefusesASubmapSideLargerThanAGrid) {
  SubmapMessage message;
  message.submap.navigable = grid::OccupancyGrid(0, 0, 0.05);
  auto sample = *ToIdl(message);
  sample.width(0xa8000000u);
  sample.height(0);
  StatusOr<SubmapMessage> refused = FromIdl(sample);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("larger than a grid"), std::string::npos);
}

TEST(StateConversionsTest, ObjectModelRoundTripsAsPercent) {
  ObjectModelMessage message;
  message.object_id = 2;
  message.template_id = 1;
  message.learning_run = 5;
  message.patch.width = 2;
  message.patch.height = 1;
  message.patch.resolution = 0.05;
  message.patch.occupancy = {0.25F, 1.0F};
  message.sightings.push_back({3, Pose2{1.0, 2.0, 0.3}});
  StatusOr<ObjectModelMessage> back = FromIdl(*ToIdl(message));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->template_id, 1u);
  EXPECT_FLOAT_EQ(back->patch.occupancy[0], 0.25F);
  EXPECT_FLOAT_EQ(back->patch.occupancy[1], 1.0F);
  ASSERT_EQ(back->sightings.size(), 1u);
  EXPECT_EQ(back->sightings[0].session, 3u);

  auto sample = *ToIdl(message);
  sample.data({50, 101});
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.sighting_x({});
  EXPECT_FALSE(FromIdl(sample).ok());
}

TEST(StateConversionsTest, RouteGraphRoundTripsAndRefusesEdgesToNowhereAndSharedIds) {
  RouteGraphMessage message;
  message.revision = 7;
  message.graph.robot_radius = 0.3;
  message.graph.clearance_margin = 0.05;
  message.graph.nodes = {{1, Point2(0.5, -1.0), route_graph::RouteNodeKind::kDoorway, 0.4, false},
                         {2, Point2(3.5, 2.0), route_graph::RouteNodeKind::kJunction, 0.8, true}};
  message.graph.edges = {{3, 4, 1, 2, 5.0, 0.38, true, 17u},
                         {5, 6, 2, 1, 4.0, 0.5, false, std::nullopt}};
  message.graph.message = "a note";
  StatusOr<RouteGraphMessage> back = FromIdl(*ToIdl(message));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->graph_id, "fleet");
  EXPECT_EQ(back->revision, 7u);
  ASSERT_EQ(back->graph.nodes.size(), 2u);
  EXPECT_EQ(back->graph.nodes[0].kind, route_graph::RouteNodeKind::kDoorway);
  EXPECT_EQ(back->graph.nodes[1].position, Point2(3.5, 2.0));
  EXPECT_FALSE(back->graph.nodes[0].predicted);
  EXPECT_TRUE(back->graph.nodes[1].predicted);
  ASSERT_EQ(back->graph.edges.size(), 2u);
  EXPECT_EQ(back->graph.edges[0].reverse_id, 4u);
  EXPECT_FLOAT_EQ(static_cast<float>(back->graph.edges[0].length), 5.0F);
  EXPECT_TRUE(back->graph.edges[0].predicted);
  EXPECT_EQ(back->graph.edges[0].blocking_object, std::optional<uint32_t>(17u));
  EXPECT_FALSE(back->graph.edges[1].predicted);
  EXPECT_EQ(back->graph.edges[1].blocking_object, std::nullopt);
  EXPECT_EQ(back->graph.message, "a note");

  auto sample = *ToIdl(message);
  sample.edge_end({9});
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.edge_id({2});  // a node's id
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.node_kind({0, 9});
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.node_x({0.5});
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.edge_flags({3, 4});  // a bit no reader knows
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.edge_object({17});
  EXPECT_FALSE(FromIdl(sample).ok());
}

TEST(StateConversionsTest, RobotFrameRoundTripsAndRefusesWhatAReaderCannotUse) {
  RobotFrameMessage frame;
  frame.robot = RobotId{"beta"};
  frame.state = RobotFrameMessage::State::kRevised;
  frame.fleet_from_map = Pose2{12.5, -3.0, 1.2};
  frame.confidence = 0.93;
  frame.overlap = 0.4;
  frame.placements = 2;
  frame.placed_against = "fleet";
  auto sample = ToIdl(frame);
  ASSERT_TRUE(sample.ok()) << sample.status();
  auto back = FromIdl(*sample);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->robot, frame.robot);
  EXPECT_EQ(back->state, frame.state);
  EXPECT_EQ(back->fleet_from_map, frame.fleet_from_map);
  EXPECT_DOUBLE_EQ(back->confidence, 0.93);
  EXPECT_NEAR(back->overlap, 0.4, 1e-6);
  EXPECT_EQ(back->placements, 2u);
  EXPECT_EQ(back->placed_against, "fleet");
  EXPECT_TRUE(back->placed());

  auto bad = *sample;
  bad.state(9);
  EXPECT_FALSE(FromIdl(bad).ok());
  bad = *sample;
  bad.fleet_from_map().theta(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(FromIdl(bad).ok());
  bad = *sample;
  bad.confidence(1.5);
  EXPECT_FALSE(FromIdl(bad).ok());
  bad = *sample;
  bad.robot_id("not a name");
  EXPECT_FALSE(FromIdl(bad).ok());
  frame.robot = RobotId{""};
  EXPECT_FALSE(ToIdl(frame).ok());
}

TEST(StateConversionsTest, ObjectTemplateRefusesMissingCells) {
  ObjectTemplateMessage message;
  message.patch.width = 3;
  message.patch.height = 3;
  message.patch.occupancy.assign(9, 0.5F);
  auto sample = *ToIdl(message);
  EXPECT_TRUE(FromIdl(sample).ok());
  sample.data({50});
  EXPECT_FALSE(FromIdl(sample).ok());
  sample = *ToIdl(message);
  sample.resolution(0.0F);
  EXPECT_FALSE(FromIdl(sample).ok());
}

}  // namespace
}  // namespace fleetmap::transport
