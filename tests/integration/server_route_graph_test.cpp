// The server's route graph over DDS between real processes (issue 37): with --route-graph, the
// fused map's graph is published on rt/fleetmap/route_graph, and published again with the next
// revision when the fused map changes; a room predicted behind a closed door is reached through
// the door by edges marked predicted. Each test uses its own random domain on loopback.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "common/extrapolation/entities_json.hpp"

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string kFleetmapBinary = std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap";

// Bounds for a loaded 2-core CI machine, not assertions about speed.
constexpr seconds kDeadline{60};

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/server_route_graph_" + std::to_string(getpid()) + "_" + name;
}

void Fill(grid::OccupancyGrid& map, double x0, double y0, double x1, double y1, int8_t value) {
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 p = map.CellCenter(x, y);
      if (p.x() >= x0 && p.x() < x1 && p.y() >= y0 && p.y() < y1) map.at(x, y) = value;
    }
  }
}

// Two 3.8 x 3.8 m rooms side by side, x in [0, 4) and [4, 8): "before" only the west one mapped,
// "after" both, joined by a 0.9 m open door in the wall between them.
std::string SaveRooms(bool after) {
  grid::OccupancyGrid map(160, 80, 0.05, Pose2{}, grid::kUnknownValue);
  Fill(map, 0.0, 0.0, after ? 8.0 : 4.05, 4.0, grid::kOccupiedValue);
  Fill(map, 0.1, 0.1, 3.95, 3.9, grid::kFreeValue);
  if (after) {
    Fill(map, 4.05, 0.1, 7.9, 3.9, grid::kFreeValue);
    Fill(map, 3.95, 1.5, 4.05, 2.4, grid::kFreeValue);
  }
  const std::string path = TempPath(after ? "after.yaml" : "before.yaml");
  const Status saved = grid::SaveMap(map, path);
  EXPECT_TRUE(saved.ok()) << saved;
  return path;
}

// The west room of SaveRooms(false) with a closed door in its east wall at y in [1.5, 2.4]: the
// door entity its robot reports.
std::string WriteClosedDoor() {
  scene::Entities entities;
  scene::DoorEntity door;
  door.id = "door_east";
  door.hinge = {4.0, 1.5};
  door.latch = {4.0, 2.4};
  door.opening_direction = {1.0, 0.0};
  door.open = false;
  entities.doors.push_back(door);
  const std::string path = TempPath("entities.json");
  std::ofstream(path) << extrapolation::EntitiesToJson(entities);
  return path;
}

class RouteGraphServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = process::RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    auto participant = transport::Participant::Create(options);
    ASSERT_TRUE(participant.ok()) << participant.status();
    participant_ = std::move(participant).value();
    auto reader = transport::RouteGraphReader::Create(*participant_, wake_up_);
    ASSERT_TRUE(reader.ok()) << reader.status();
    reader_ = std::move(reader).value();
  }

  // The newest graph that satisfies `done`, or nothing by the deadline.
  template <typename Done>
  std::optional<transport::RouteGraphMessage> WaitFor(Done done) {
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up_->WaitFor(milliseconds(100));
      for (auto& event : reader_->Drain()) {
        EXPECT_NE(event.kind, transport::RouteGraphEvent::Kind::kRejected) << event.error;
        if (event.kind != transport::RouteGraphEvent::Kind::kSample) continue;
        if (done(event.message)) return event.message;
      }
    }
    return std::nullopt;
  }

  int domain_ = 0;
  std::map<std::string, std::string> env_;
  std::unique_ptr<transport::Participant> participant_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::RouteGraphReader> reader_;
};

// Whether an edge of the graph crosses the wall at x = 3.95..4.05, and whether all that do are
// marked predicted.
struct WallCrossings {
  int edges = 0;
  int predicted = 0;
};
WallCrossings CrossingsOf(const route_graph::RouteGraph& graph) {
  WallCrossings crossings;
  for (const route_graph::RouteEdge& edge : graph.edges) {
    const double a = graph.FindNode(edge.start)->position.x();
    const double b = graph.FindNode(edge.end)->position.x();
    if ((a < 3.95) != (b < 3.95)) {
      ++crossings.edges;
      crossings.predicted += edge.predicted ? 1 : 0;
    }
  }
  return crossings;
}

TEST_F(RouteGraphServerTest, ARoomPredictedBehindAClosedDoorIsReachedByPredictedEdges) {
  process::Subprocess server({testing::kServerBinary, "--duration", "120", "--map-period", "0.3",
                              "--route-graph", "--route-graph-radius", "0.25"},
                             env_);
  ASSERT_TRUE(server.started());
  process::Subprocess alpha({testing::kAgentBinary, "--robot-id", "alpha", "--map",
                             SaveRooms(false), "--entities", WriteClosedDoor()},
                            env_);
  ASSERT_TRUE(alpha.started());
  const auto predicted = WaitFor([](const transport::RouteGraphMessage& message) {
    return CrossingsOf(message.graph).edges > 0;
  });
  ASSERT_TRUE(predicted.has_value()) << server.Output();
  const WallCrossings crossings = CrossingsOf(predicted->graph);
  EXPECT_EQ(crossings.predicted, crossings.edges) << "every way through the shut door is predicted";
  int east_nodes = 0;
  for (const route_graph::RouteNode& node : predicted->graph.nodes) {
    if (node.position.x() > 4.2) {
      EXPECT_TRUE(node.predicted) << "node " << node.id << " stands where nobody looked";
      ++east_nodes;
    }
  }
  EXPECT_GT(east_nodes, 0);
  for (const route_graph::RouteEdge& edge : predicted->graph.edges) {
    const double a = predicted->graph.FindNode(edge.start)->position.x();
    const double b = predicted->graph.FindNode(edge.end)->position.x();
    if (std::max(a, b) < 3.8) {
      EXPECT_FALSE(edge.predicted) << "edge " << edge.id;
    }
  }

  // `fleetmap route-graph --live` writes the fleet's graph for nav2_route, marks and all.
  const std::string geojson_path = TempPath("live.geojson");
  const process::CommandResult exported = process::RunCommand(
      {kFleetmapBinary, "route-graph", "--live", "--domain", std::to_string(domain_),
       "--localhost-only", "--out", geojson_path, "--timeout", "30"},
      kDeadline);
  ASSERT_EQ(exported.exit_code, 0) << exported.output();
  EXPECT_NE(exported.out.find("through predicted space"), std::string::npos) << exported.out;
  std::ifstream geojson_file(geojson_path);
  const nlohmann::json geojson = nlohmann::json::parse(geojson_file);
  int exported_predicted = 0;
  for (const nlohmann::json& feature : geojson.at("features")) {
    if (feature.at("geometry").at("type") != "MultiLineString") continue;
    exported_predicted += feature.at("properties").at("metadata").at("predicted").get<bool>();
  }
  EXPECT_GE(exported_predicted, 2 * crossings.edges) << "each edge both ways";

  server.Signal(SIGINT);
  EXPECT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("through predicted space"), std::string::npos) << server.Output();
}

TEST_F(RouteGraphServerTest, LiveExportWithoutAServerSaysSoAndExitsOne) {
  const process::CommandResult none = process::RunCommand(
      {kFleetmapBinary, "route-graph", "--live", "--domain", std::to_string(domain_),
       "--localhost-only", "--out", TempPath("none.geojson"), "--timeout", "1"},
      kDeadline);
  EXPECT_EQ(none.exit_code, 1) << none.output();
  EXPECT_NE(none.err.find("no route graph on rt/fleetmap/route_graph within 1 s on DDS domain " +
                          std::to_string(domain_)),
            std::string::npos)
      << none.err;
  const process::CommandResult both = process::RunCommand(
      {kFleetmapBinary, "route-graph", "map.yaml", "--live", "--out", TempPath("x.geojson")},
      kDeadline);
  EXPECT_EQ(both.exit_code, 2) << both.output();
  EXPECT_NE(both.err.find("one of them"), std::string::npos) << both.err;
}

TEST_F(RouteGraphServerTest, PublishesTheFusedMapsGraphAndANewRevisionWhenTheMapGrows) {
  auto east_nodes = [](const transport::RouteGraphMessage& message) {
    int count = 0;
    for (const route_graph::RouteNode& node : message.graph.nodes) {
      count += node.position.x() > 4.5 ? 1 : 0;
    }
    return count;
  };

  process::Subprocess server({testing::kServerBinary, "--duration", "120", "--map-period", "0.3",
                              "--route-graph", "--route-graph-radius", "0.25"},
                             env_);
  ASSERT_TRUE(server.started());
  process::Subprocess alpha(
      {testing::kAgentBinary, "--robot-id", "alpha", "--map", SaveRooms(false)}, env_);
  ASSERT_TRUE(alpha.started());
  const auto first = WaitFor(
      [](const transport::RouteGraphMessage& message) { return !message.graph.nodes.empty(); });
  ASSERT_TRUE(first.has_value()) << server.Output();
  EXPECT_EQ(first->graph_id, "fleet");
  EXPECT_GE(first->revision, 1u);
  EXPECT_DOUBLE_EQ(first->graph.robot_radius, 0.25);
  EXPECT_EQ(east_nodes(*first), 0) << "nothing is mapped east of the wall yet";

  process::Subprocess beta({testing::kAgentBinary, "--robot-id", "beta", "--map", SaveRooms(true)},
                           env_);
  ASSERT_TRUE(beta.started());
  const auto grown = WaitFor([&](const transport::RouteGraphMessage& message) {
    return message.revision > first->revision && east_nodes(message) > 0;
  });
  ASSERT_TRUE(grown.has_value()) << server.Output();
  // Through the open door the two rooms are one part: an edge crosses the wall.
  bool crosses = false;
  for (const route_graph::RouteEdge& edge : grown->graph.edges) {
    const double a = grown->graph.FindNode(edge.start)->position.x();
    const double b = grown->graph.FindNode(edge.end)->position.x();
    crosses |= (a < 3.95) != (b < 3.95);
  }
  EXPECT_TRUE(crosses);
  server.Signal(SIGINT);
  EXPECT_EQ(server.Wait(kDeadline), 0) << server.Output();
}

}  // namespace
}  // namespace fleetmap
