#include "view/fleet_view_model.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/transport/topics.hpp"

namespace fleetmap::view {
namespace {

using nlohmann::json;
using std::chrono::milliseconds;
using std::chrono::seconds;

const Timestamp kStart = Timestamp() + std::chrono::hours(500000);

transport::TileEvent FusedTile(int x, int y, uint32_t revision) {
  transport::TileEvent event;
  event.tile.robot_id = RobotId{"fleet"};
  event.tile.tile = TileId{x, y};
  event.tile.revision = revision;
  vector_map::Polyline wall;
  wall.points = {Point2(x * 10.0, y * 10.0), Point2(x * 10.0 + 3.0, y * 10.0)};
  wall.half_width = 0.05;
  event.tile.map.obstacles.push_back(wall);
  event.tile.map.free_space.push_back(
      {{Point2(x * 10.0, y * 10.0 + 1), Point2(x * 10.0 + 2, y * 10.0 + 1),
        Point2(x * 10.0 + 2, y * 10.0 + 2)},
       {}});
  return event;
}

transport::RobotEvent Status(const std::string& robot, double x) {
  RobotStatus status;
  status.robot = RobotId{robot};
  status.map_from_robot = Pose2{x, 2.0, 0.5};
  status.fleet_from_map = Pose2{10.0, 0.0, 0.0};
  status.map_revision = 3;
  return transport::RobotEvent::Alive(status);
}

json Parse(const std::optional<std::string>& event) {
  EXPECT_TRUE(event.has_value());
  return event ? json::parse(*event) : json();
}

transport::FleetServerEvent Server(const std::string& name, int32_t strength, bool serving) {
  transport::FleetServerEvent event;
  event.message.server_id = name + "-id";
  event.message.name = name;
  event.message.ownership_strength = strength;
  event.message.serving = serving;
  event.message.robots = 1;
  return event;
}

TEST(FleetViewModelTest, TheStatusNamesTheServingServerAndSaysWhenNoneIsLeft) {
  FleetViewModel model;
  model.OnRobotEvent(Status("alpha", 1.0), kStart);
  model.Tick(kStart);
  EXPECT_TRUE(json::parse(model.FullEvent())["status"]["server"].is_null());
  EXPECT_EQ(json::parse(model.FullEvent())["robots"]["alpha"]["state"], "live")
      << "no server was ever heard: the robot is not stale for it";

  model.OnServer(Server("b", 50, false), kStart);
  model.OnServer(Server("a", 100, true), kStart);
  model.Tick(kStart + milliseconds(100));
  json server = json::parse(model.FullEvent())["status"]["server"];
  EXPECT_EQ(server["name"], "a");
  EXPECT_EQ(server["standbys"], 1);

  // a is killed; b serves.
  const Timestamp failover = kStart + milliseconds(1600);
  model.OnServer(Server("b", 50, true), failover);
  model.OnRobotEvent(Status("alpha", 1.5), failover);
  model.Tick(failover);
  server = json::parse(model.FullEvent())["status"]["server"];
  EXPECT_EQ(server["name"], "b");
  EXPECT_EQ(server["standbys"], 0);

  // b dies too: within the silence limit the page says there is no server, and the robot that
  // still sends its status is stale, since nothing fuses what it sends.
  const Timestamp none = failover + seconds(2);
  model.OnRobotEvent(Status("alpha", 2.0), none);
  model.Tick(none);
  const json full = json::parse(model.FullEvent());
  EXPECT_TRUE(full["status"]["server"].is_null());
  EXPECT_EQ(full["robots"]["alpha"]["state"], "stale");
}

// Shards (docs/shards.md): each shard's serving server and region; no shard stands by for another.
TEST(FleetViewModelTest, TheStatusNamesEachShardItsServerAndItsRegion) {
  FleetViewModel model;
  const auto shard = [](const std::string& name, const std::string& shard_name, int32_t strength,
                        double min_x, double max_x) {
    transport::FleetServerEvent event = Server(name, strength, true);
    event.message.shard = shard_name;
    event.message.region = {min_x, 0.0, max_x, 80.0};
    return event;
  };
  model.OnServer(shard("west", "west", 100, 0.0, 60.0), kStart);
  model.OnServer(shard("west-standby", "west", 50, 0.0, 60.0), kStart);
  model.OnServer(shard("east", "east", 10, 60.0, 120.0), kStart);
  model.Tick(kStart + milliseconds(100));
  const json server = json::parse(model.FullEvent())["status"]["server"];
  ASSERT_FALSE(server.is_null()) << "shards serve the fleet";
  EXPECT_FALSE(server.contains("name")) << "no unsharded server";
  ASSERT_EQ(server["shards"].size(), 2u);
  EXPECT_EQ(server["shards"][0]["name"], "east");
  EXPECT_EQ(server["shards"][0]["server"], "east");
  EXPECT_EQ(server["shards"][0]["standbys"], 0);
  EXPECT_EQ(server["shards"][1]["server"], "west");
  EXPECT_EQ(server["shards"][1]["standbys"], 1);
  EXPECT_EQ(server["shards"][1]["region"], json::parse("[0.0, 0.0, 60.0, 80.0]"));
}

TEST(FleetViewModelTest, AServerThatWithdrewIsGoneAtOnce) {
  FleetViewModel model;
  model.OnServer(Server("a", 100, true), kStart);
  transport::FleetServerEvent withdrawn = Server("a", 100, true);
  withdrawn.kind = transport::FleetServerEvent::Kind::kRemoved;
  model.OnServer(withdrawn, kStart + milliseconds(10));
  model.Tick(kStart + milliseconds(20));
  EXPECT_TRUE(json::parse(model.FullEvent())["status"]["server"].is_null());
}

TEST(FleetViewModelTest, ADeltaHoldsOnlyWhatChanged) {
  FleetViewModel model;
  model.OnFusedTile(FusedTile(0, 0, 1));
  model.OnFusedTile(FusedTile(1, 0, 1));
  model.Tick(kStart);
  const json first = Parse(model.TakeDelta());
  EXPECT_EQ(first["type"], "delta");
  EXPECT_EQ(first["tiles"].size(), 2u);
  EXPECT_EQ(first["status"]["tiles"], 2);

  // Nothing new: no delta at all.
  model.Tick(kStart + milliseconds(200));
  EXPECT_FALSE(model.TakeDelta().has_value());

  // The same tile again is no change; a new revision of one tile is.
  model.OnFusedTile(FusedTile(0, 0, 1));
  model.OnFusedTile(FusedTile(1, 0, 2));
  model.Tick(kStart + milliseconds(400));
  const json second = Parse(model.TakeDelta());
  ASSERT_EQ(second["tiles"].size(), 1u);
  EXPECT_EQ(second["tiles"]["1,0"]["rev"], 2);
  EXPECT_FALSE(second.contains("status")) << "the status line did not change";
  EXPECT_GT(second["seq"].get<int>(), first["seq"].get<int>());

  // A removed tile goes out as null.
  transport::TileEvent removed;
  removed.kind = transport::TileEvent::Kind::kRemoved;
  removed.tile.tile = TileId{0, 0};
  model.OnFusedTile(removed);
  model.Tick(kStart + milliseconds(600));
  const json third = Parse(model.TakeDelta());
  EXPECT_TRUE(third["tiles"]["0,0"].is_null());
  EXPECT_EQ(third["status"]["tiles"], 1);
}

TEST(FleetViewModelTest, TheWholeStateHoldsEverythingSoFar) {
  FleetViewModel model;
  model.OnFusedTile(FusedTile(0, 0, 1));
  model.OnFusedTile(FusedTile(0, 1, 1));
  model.OnRobotEvent(Status("alpha", 1.0), kStart);
  model.Tick(kStart);
  const std::optional<std::string> delta = model.TakeDelta();
  const json full = json::parse(model.FullEvent());
  EXPECT_EQ(full["type"], "full");
  EXPECT_EQ(full["seq"], json::parse(*delta)["seq"]) << "the whole state includes that delta";
  EXPECT_EQ(full["tiles"].size(), 2u);
  ASSERT_TRUE(full["robots"].contains("alpha"));
  // The tile's geometry, in metres: one obstacle [half width, closed, x0, y0, x1, y1].
  EXPECT_EQ(full["tiles"]["0,1"]["ob"][0], json({0.05, 0, 0.0, 10.0, 3.0, 10.0}));
  EXPECT_EQ(full["tiles"]["0,1"]["fr"][0][0].size(), 6u);
  // The cell size, which the page widens the free outlines by (they pass through cell centres).
  EXPECT_EQ(full["tiles"]["0,1"]["res"], 0.05);
}

TEST(FleetViewModelTest, RobotsAreShownInTheFleetFrameAndTurnStaleThenLost) {
  FleetViewModel model;
  model.OnRobotEvent(Status("alpha", 1.0), kStart);
  model.Tick(kStart);
  const json alpha = Parse(model.TakeDelta())["robots"]["alpha"];
  EXPECT_EQ(alpha["state"], "live");
  EXPECT_DOUBLE_EQ(alpha["x"].get<double>(), 11.0) << "fleet_from_map moves it 10 m";
  EXPECT_DOUBLE_EQ(alpha["y"].get<double>(), 2.0);
  EXPECT_EQ(alpha["rev"], 3);

  // Moving: a delta carries only the point the path gained; the whole state, the whole path.
  model.OnRobotEvent(Status("alpha", 2.0), kStart + milliseconds(500));
  model.Tick(kStart + milliseconds(500));
  const json moved = Parse(model.TakeDelta());
  EXPECT_EQ(moved["robots"]["alpha"]["x"], 12.0);
  EXPECT_EQ(moved["path_points"]["alpha"], json::parse("[[12.0, 2.0]]"));
  EXPECT_EQ(json::parse(model.FullEvent())["paths"]["alpha"],
            json::parse("[[11.0, 2.0, 12.0, 2.0]]"));

  // Silent past stale_after: stale; then DDS says lost.
  model.Tick(kStart + seconds(3));
  EXPECT_EQ(Parse(model.TakeDelta())["robots"]["alpha"]["state"], "stale");
  model.OnRobotEvent(
      transport::RobotEvent::Gone(transport::RobotEvent::Kind::kLost, RobotId{"alpha"}, "writer"),
      kStart + seconds(3));
  model.Tick(kStart + seconds(3));
  const json lost = Parse(model.TakeDelta());
  EXPECT_EQ(lost["robots"]["alpha"]["state"], "lost");
  EXPECT_EQ(lost["status"]["lost"], 1);
  EXPECT_EQ(lost["status"]["live"], 0);
}

transport::RobotEvent Gone(transport::RobotEvent::Kind kind, const std::string& robot) {
  return transport::RobotEvent::Gone(kind, RobotId{robot}, "writer");
}

std::string StateOf(const FleetViewModel& model, const std::string& robot) {
  return json::parse(model.FullEvent())["robots"][robot]["state"];
}

TEST(FleetViewModelTest, ARobotThatLeftStaysLeftWhenItsWriterGoesToo) {
  FleetViewModel model;
  model.OnRobotEvent(Status("polite", 1.0), kStart);
  model.OnRobotEvent(Status("killed", 1.0), kStart);
  model.Tick(kStart);
  // A clean exit disposes the status (left), then the agent's writer goes, which DDS reports as
  // well (lost); a killed agent's lease lapses (lost), and its writer is dropped later (lost).
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLeft, "polite"), kStart);
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLost, "polite"), kStart);
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLost, "killed"), kStart);
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLeft, "killed"), kStart);
  model.Tick(kStart + seconds(5));
  EXPECT_EQ(StateOf(model, "polite"), "left");
  EXPECT_EQ(StateOf(model, "killed"), "lost");
  EXPECT_EQ(json::parse(model.FullEvent())["status"]["lost"], 1);

  // Back with a status: live again, and it can leave again.
  model.OnRobotEvent(Status("polite", 1.5), kStart + seconds(6));
  model.Tick(kStart + seconds(6));
  EXPECT_EQ(StateOf(model, "polite"), "live");
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLeft, "polite"), kStart + seconds(6));
  EXPECT_EQ(StateOf(model, "polite"), "left");
}

TEST(FleetViewModelTest, AStaleRobotCanStillLeave) {
  FleetViewModel model;
  model.OnRobotEvent(Status("alpha", 1.0), kStart);
  model.Tick(kStart + seconds(2));
  EXPECT_EQ(StateOf(model, "alpha"), "stale");
  model.OnRobotEvent(Gone(transport::RobotEvent::Kind::kLeft, "alpha"), kStart + seconds(2));
  model.Tick(kStart + seconds(3));
  EXPECT_EQ(StateOf(model, "alpha"), "left") << "a left robot does not turn stale";
}

TEST(FleetViewModelTest, APlacementStartsANewPathRun) {
  FleetViewModel model;
  RobotStatus status;
  status.robot = RobotId{"bravo"};
  status.tiles_in_map_frame = true;
  const auto at = [&](double x, Timestamp now) {
    status.map_from_robot = Pose2{x, 0.0, 0.0};
    model.OnRobotEvent(transport::RobotEvent::Alive(status), now);
    model.Tick(now);
  };
  at(1.0, kStart);
  at(2.0, kStart + milliseconds(100));
  EXPECT_EQ(Parse(model.TakeDelta())["path_points"]["bravo"],
            json::parse("[[], [1.0, 0.0, 2.0, 0.0]]"))
      << "the first point starts the first run";

  // Placed 5 m up: the next pose starts a new run; no segment joins (2, 0) to (3, 5).
  transport::RobotFrameEvent frame;
  frame.message.robot = RobotId{"bravo"};
  frame.message.state = transport::RobotFrameMessage::State::kPlaced;
  frame.message.fleet_from_map = Pose2{0.0, 5.0, 0.0};
  model.OnRobotFrame(frame);
  at(3.0, kStart + milliseconds(200));
  at(4.0, kStart + milliseconds(300));
  EXPECT_EQ(Parse(model.TakeDelta())["path_points"]["bravo"],
            json::parse("[[], [3.0, 5.0, 4.0, 5.0]]"));

  // The same placement again (its standing changed, say) continues the run; a revision that
  // moves the frame starts another.
  model.OnRobotFrame(frame);
  at(5.0, kStart + milliseconds(400));
  frame.message.state = transport::RobotFrameMessage::State::kRevised;
  frame.message.fleet_from_map = Pose2{0.0, 6.0, 0.0};
  model.OnRobotFrame(frame);
  at(6.0, kStart + milliseconds(500));
  EXPECT_EQ(Parse(model.TakeDelta())["path_points"]["bravo"],
            json::parse("[[5.0, 5.0], [6.0, 6.0]]"));
  EXPECT_EQ(json::parse(model.FullEvent())["paths"]["bravo"],
            json::parse("[[1.0, 0.0, 2.0, 0.0], [3.0, 5.0, 4.0, 5.0, 5.0, 5.0], [6.0, 6.0]]"));
}

transport::TileEvent RobotTile(const std::string& robot, int x, int y) {
  transport::TileEvent event = FusedTile(x, y, 1);
  event.tile.robot_id = RobotId{robot};
  return event;
}

TEST(FleetViewModelTest, AnUnplacedRobotsOwnTilesAreShownUntilItIsPlaced) {
  FleetViewModel model;
  RobotStatus unplaced;
  unplaced.robot = RobotId{"bravo"};
  unplaced.tiles_in_map_frame = true;
  RobotStatus given;
  given.robot = RobotId{"alpha"};

  // A tile before the robot's first status is kept, not shown: nobody knows its frame yet.
  model.OnRobotTile(RobotTile("bravo", 0, 0));
  model.OnRobotTile(RobotTile("alpha", 0, 0));
  model.Tick(kStart);
  EXPECT_FALSE(Parse(model.TakeDelta()).contains("own_tiles"));
  model.OnRobotEvent(transport::RobotEvent::Alive(unplaced), kStart);
  model.OnRobotEvent(transport::RobotEvent::Alive(given), kStart);
  model.OnRobotTile(RobotTile("bravo", 1, 0));
  model.OnRobotTile(RobotTile("alpha", 1, 0));
  model.Tick(kStart);
  const json shown = Parse(model.TakeDelta())["own_tiles"];
  ASSERT_EQ(shown.size(), 2u) << shown;
  EXPECT_EQ(shown["bravo/0,0"]["robot"], "bravo");
  EXPECT_EQ(shown["bravo/1,0"]["ob"][0], json({0.05, 0, 10.0, 0.0, 13.0, 0.0}));
  EXPECT_EQ(json::parse(model.FullEvent())["own_tiles"].size(), 2u);

  // A removed tile goes; once placed, the fused map holds them, and later ones are not kept.
  transport::TileEvent removed = RobotTile("bravo", 1, 0);
  removed.kind = transport::TileEvent::Kind::kRemoved;
  model.OnRobotTile(removed);
  model.Tick(kStart);
  EXPECT_TRUE(Parse(model.TakeDelta())["own_tiles"]["bravo/1,0"].is_null());
  transport::RobotFrameEvent frame;
  frame.message.robot = RobotId{"bravo"};
  frame.message.state = transport::RobotFrameMessage::State::kPlaced;
  model.OnRobotFrame(frame);
  model.OnRobotTile(RobotTile("bravo", 2, 0));
  model.Tick(kStart);
  EXPECT_EQ(Parse(model.TakeDelta())["own_tiles"], json::parse(R"({"bravo/0,0": null})"));
  EXPECT_TRUE(json::parse(model.FullEvent())["own_tiles"].empty());
}

TEST(FleetViewModelTest, APlacementFromTheServerMovesTheRobot) {
  FleetViewModel model;
  RobotStatus status;
  status.robot = RobotId{"bravo"};
  status.map_from_robot = Pose2{1.0, 0.0, 0.0};
  status.tiles_in_map_frame = true;
  model.OnRobotEvent(transport::RobotEvent::Alive(status), kStart);
  model.Tick(kStart);
  EXPECT_EQ(Parse(model.TakeDelta())["robots"]["bravo"]["placement"], "unplaced");

  transport::RobotFrameEvent frame;
  frame.message.robot = RobotId{"bravo"};
  frame.message.state = transport::RobotFrameMessage::State::kPlaced;
  frame.message.fleet_from_map = Pose2{0.0, 5.0, 0.0};
  model.OnRobotFrame(frame);
  model.Tick(kStart + milliseconds(100));
  const json bravo = Parse(model.TakeDelta())["robots"]["bravo"];
  EXPECT_EQ(bravo["placement"], "placed");
  EXPECT_DOUBLE_EQ(bravo["y"].get<double>(), 5.0);
}

TEST(FleetViewModelTest, WireRatesAndLatencyComeFromTheRobotsTiles) {
  FleetViewModel model;
  model.OnRobotEvent(Status("alpha", 1.0), kStart);
  for (int i = 0; i < 10; ++i) {
    transport::TileEvent tile = FusedTile(i, 0, 1);
    tile.tile.robot_id = RobotId{"alpha"};
    tile.serialized_bytes = 1000;
    tile.tile.stamp = kStart + milliseconds(500 * i);
    tile.received = tile.tile.stamp + milliseconds(20);
    model.OnRobotTile(tile);
  }
  model.Tick(kStart + milliseconds(4600));
  const json alpha = Parse(model.TakeDelta())["robots"]["alpha"];
  // Ten tiles of 1000 bytes over the 4.58 s since the first arrived.
  EXPECT_NEAR(alpha["bps"].get<double>(), 10000.0 / 4.58, 1.0);
  EXPECT_NEAR(alpha["ups"].get<double>(), 10 / 4.58, 0.06);
  EXPECT_NEAR(alpha["latency_ms"].get<double>(), 20.0, 0.1);
}

TEST(FleetViewModelTest, RefusedSamplesAreCountedByTopic) {
  FleetViewModel model;
  transport::TileEvent bad;
  bad.kind = transport::TileEvent::Kind::kRejected;
  model.OnFusedTile(bad);
  model.OnFusedTile(bad);
  model.OnRobotEvent(transport::RobotEvent::Rejected(InvalidArgumentError("bad")), kStart);
  model.Tick(kStart);
  const json status = Parse(model.TakeDelta())["status"];
  EXPECT_EQ(status["rejected"], 3);
  EXPECT_EQ(status["rejected_by_topic"][transport::kFusedTilesTopic], 2);
  EXPECT_EQ(status["rejected_by_topic"][transport::kRobotStatusTopic], 1);
}

TEST(FleetViewModelTest, PredictionsCarryTheirStateAndOutline) {
  FleetViewModel model;
  transport::SubmapEvent event;
  event.message.submap.id = 4;
  event.message.submap.kind = scene::SubmapKind::kPredictedDoor;
  event.message.submap.navigable = grid::OccupancyGrid(10, 10, 0.1);
  for (int y = 2; y < 8; ++y) {
    for (int x = 2; x < 8; ++x) event.message.submap.navigable.at(x, y) = grid::kFreeValue;
  }
  event.message.state = scene::SubmapState::kConfirmed;
  event.message.precision = 0.96F;
  model.OnSubmap(event);
  model.Tick(kStart);
  const json delta = Parse(model.TakeDelta());
  const json& submap = delta["submaps"]["4"];
  EXPECT_EQ(submap["state"], "confirmed");
  EXPECT_EQ(submap["kind"], "predicted_door");
  EXPECT_NEAR(submap["precision"].get<double>(), 0.96, 1e-3);
  ASSERT_EQ(submap["rings"].size(), 1u);
  // The outline runs through the centres of the free block's border cells: 0.25 .. 0.75 m.
  double min_x = 1e9;
  double max_x = -1e9;
  const json& ring = submap["rings"][0];
  for (size_t i = 0; i < ring.size(); i += 2) {
    min_x = std::min(min_x, ring[i].get<double>());
    max_x = std::max(max_x, ring[i].get<double>());
  }
  EXPECT_NEAR(min_x, 0.25, 1e-6);
  EXPECT_NEAR(max_x, 0.75, 1e-6);
  EXPECT_EQ(delta["status"]["submaps"]["confirmed"], 1);
}

TEST(FleetViewModelTest, TheRouteGraphIsItsNodesAndEdgesByIndexUntilWithdrawn) {
  FleetViewModel model;
  transport::RouteGraphEvent event;
  event.message.revision = 3;
  event.message.graph.robot_radius = 0.25;
  event.message.graph.nodes = {
      {10, Point2(1.0, 2.0), route_graph::RouteNodeKind::kDoorway, 0.4, false},
      {11, Point2(4.0, 2.0), route_graph::RouteNodeKind::kJunction, 0.9, false},
      {12, Point2(4.0, 6.5), route_graph::RouteNodeKind::kDeadEnd, 0.5, false}};
  event.message.graph.edges = {{20, 21, 10, 11, 3.0, 0.4, false, std::nullopt},
                               {22, 23, 11, 12, 4.5, 0.5, true, 7u}};
  model.OnRouteGraph(event);
  const json delta = Parse(model.TakeDelta());
  const json& graph = delta["route_graphs"]["fleet"];
  EXPECT_EQ(graph["revision"], 3);
  EXPECT_EQ(graph["radius"], 0.25);
  EXPECT_EQ(graph["nodes"], json({1.0, 2.0, 4.0, 2.0, 4.0, 6.5}));
  EXPECT_EQ(graph["kinds"], json({"doorway", "junction", "dead_end"}));
  EXPECT_EQ(graph["edges"], json({{0, 1}, {1, 2}}));  // node indices, not ids
  EXPECT_EQ(graph["predicted"], json({1}));           // edge indices
  EXPECT_EQ(graph["blocked"], json({{1, 7}}));        // edge index, object id
  EXPECT_EQ(Parse(model.FullEvent())["route_graphs"]["fleet"], graph);

  transport::RouteGraphEvent withdrawn;
  withdrawn.kind = transport::RouteGraphEvent::Kind::kRemoved;
  model.OnRouteGraph(withdrawn);
  EXPECT_TRUE(Parse(model.TakeDelta())["route_graphs"]["fleet"].is_null());
  EXPECT_TRUE(Parse(model.FullEvent())["route_graphs"].empty());
}

TEST(FleetViewModelTest, NoPeerCanMakeTheViewHoldMoreThanItsBounds) {
  ViewModelOptions options;
  options.max_robots = 2;
  options.max_items = 3;
  FleetViewModel model(options);
  for (int i = 0; i < 10; ++i) {
    model.OnFusedTile(FusedTile(i, 0, 1));
    model.OnRobotEvent(Status("robot" + std::to_string(i), 1.0), kStart);
  }
  // Known ones still update.
  model.OnFusedTile(FusedTile(0, 0, 2));
  model.Tick(kStart);
  const json delta = Parse(model.TakeDelta());
  EXPECT_EQ(delta["tiles"].size(), 3u);
  EXPECT_EQ(delta["tiles"]["0,0"]["rev"], 2);
  EXPECT_EQ(delta["robots"].size(), 2u);
  EXPECT_EQ(delta["status"]["rejected_by_topic"][transport::kFusedTilesTopic], 7);
  EXPECT_EQ(delta["status"]["rejected_by_topic"][transport::kRobotStatusTopic], 8);
  // A robot the view never held cannot be lost either.
  model.OnRobotEvent(
      transport::RobotEvent::Gone(transport::RobotEvent::Kind::kLost, RobotId{"robot9"}, "writer"),
      kStart);
  EXPECT_EQ(model.robot_count(), 2u);
}

}  // namespace
}  // namespace fleetmap::view
