// The server's route graph over DDS between real processes (issue 37): with --route-graph, the
// fused map's graph is published on rt/fleetmap/route_graph, and published again with the next
// revision when the fused map changes. Each test uses its own random domain on loopback.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

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

TEST(RouteGraphServerTest, PublishesTheFusedMapsGraphAndANewRevisionWhenTheMapGrows) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  auto participant = transport::Participant::Create(options);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RouteGraphReader::Create(**participant, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  // The newest graph that satisfies `done`, or nothing by the deadline.
  auto wait_for = [&](auto done) -> std::optional<transport::RouteGraphMessage> {
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up->WaitFor(milliseconds(100));
      for (auto& event : (*reader)->Drain()) {
        EXPECT_NE(event.kind, transport::RouteGraphEvent::Kind::kRejected) << event.error;
        if (event.kind != transport::RouteGraphEvent::Kind::kSample) continue;
        if (done(event.message)) return event.message;
      }
    }
    return std::nullopt;
  };
  auto east_nodes = [](const transport::RouteGraphMessage& message) {
    int count = 0;
    for (const route_graph::RouteNode& node : message.graph.nodes) {
      count += node.position.x() > 4.5 ? 1 : 0;
    }
    return count;
  };

  process::Subprocess server({testing::kServerBinary, "--duration", "120", "--map-period", "0.3",
                              "--route-graph", "--route-graph-radius", "0.25"},
                             env);
  ASSERT_TRUE(server.started());
  process::Subprocess alpha(
      {testing::kAgentBinary, "--robot-id", "alpha", "--map", SaveRooms(false)}, env);
  ASSERT_TRUE(alpha.started());
  const auto first = wait_for(
      [](const transport::RouteGraphMessage& message) { return !message.graph.nodes.empty(); });
  ASSERT_TRUE(first.has_value()) << server.Output();
  EXPECT_EQ(first->graph_id, "fleet");
  EXPECT_GE(first->revision, 1u);
  EXPECT_DOUBLE_EQ(first->graph.robot_radius, 0.25);
  EXPECT_EQ(east_nodes(*first), 0) << "nothing is mapped east of the wall yet";

  process::Subprocess beta({testing::kAgentBinary, "--robot-id", "beta", "--map", SaveRooms(true)},
                           env);
  ASSERT_TRUE(beta.started());
  const auto grown = wait_for([&](const transport::RouteGraphMessage& message) {
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
