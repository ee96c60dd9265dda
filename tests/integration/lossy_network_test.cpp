// A fleet on a lossy network (issue 15): a real server and agents in a network namespace of their
// own whose nftables rule drops 20 % of the UDP datagrams at random. No live robot may be
// reported lost, and every robot tile, first and updated, must reach the fused map. Needs root,
// ip and nft; skipped otherwise. Latency under loss is a benchmark figure, not asserted here:
// `fleetmap bench loss` measures it (docs/results.md).

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "common/grid/map_io.hpp"
#include "common/process/lossy_network_namespace.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using process::LossyNetworkNamespace;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;
using std::chrono::steady_clock;

// Bound the waits (the fleet needs more round trips at 20 % loss); they are not assertions.
constexpr seconds kDeadline{60};
// How long the whole fleet runs under loss, statuses and all, before it leaves: 15 liveliness
// leases, where Fast DDS's default timings reported live robots lost several times.
constexpr seconds kSoak{30};
constexpr double kTileSize = 10.0;  // the agents' default

struct Robot {
  std::string name;
  std::string map_path;
  Pose2 fleet_from_map;
  std::unique_ptr<Subprocess> agent;
};

// A map_server map of rooms with a few unknown patches; `wall_row` >= 0 adds a wall along that
// row (the edit the agent must send again under loss).
grid::OccupancyGrid MakeMap(int width, int height, int wall_row = -1) {
  grid::OccupancyGrid map(width, height, 0.05, Pose2{-3.0, 1.5, 0.0}, grid::kFreeValue);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (x % 40 == 0 || y % 30 == 0 || y == wall_row) map.at(x, y) = grid::kOccupiedValue;
      if ((x / 7 + y / 5) % 11 == 0) map.at(x, y) = grid::kUnknownValue;
    }
  }
  return map;
}

// The fleet-frame tiles holding a known cell of `map`: those the server must fuse.
std::set<TileId> KnownTiles(const grid::OccupancyGrid& map, const Pose2& fleet_from_map) {
  std::set<TileId> tiles;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (map.StateAt(x, y) == grid::CellState::kUnknown) continue;
      const Point2 fleet = fleet_from_map.ToTransform() * map.CellCenter(x, y);
      tiles.insert(TileId{static_cast<int32_t>(std::floor(fleet.x() / kTileSize)),
                          static_cast<int32_t>(std::floor(fleet.y() / kTileSize))});
    }
  }
  return tiles;
}

// Share of the known cells of `source` that `fused` gives the same state; with `only_row` >= 0,
// of the cells of that row only.
double Agreement(const grid::OccupancyGrid& source, const Pose2& fleet_from_map,
                 const grid::OccupancyGrid& fused, int only_row = -1) {
  int64_t known = 0, same = 0;
  for (int y = 0; y < source.height(); ++y) {
    if (only_row >= 0 && y != only_row) continue;
    for (int x = 0; x < source.width(); ++x) {
      const grid::CellState state = source.StateAt(x, y);
      if (state == grid::CellState::kUnknown) continue;
      ++known;
      const auto cell = fused.CellAt(fleet_from_map.ToTransform() * source.CellCenter(x, y));
      if (cell && fused.StateAt(cell->x, cell->y) == state) ++same;
    }
  }
  return known == 0 ? 0.0 : static_cast<double>(same) / known;
}

size_t Count(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

class LossyNetworkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const Status available = LossyNetworkNamespace::CheckAvailable(); !available.ok()) {
      GTEST_SKIP() << "the lossy-network test " << available.message()
                   << "; run the tests as root with iproute2 and nftables to include it";
    }
  }
};

TEST_F(LossyNetworkTest, AtTwentyPercentLossNoLiveRobotIsLostAndEveryTileArrives) {
  auto network = LossyNetworkNamespace::Create(20);
  if (network.status().code() == StatusCode::kUnavailable) {
    GTEST_SKIP() << "the lossy-network test cannot make a network namespace here: "
                 << network.status();
  }
  ASSERT_TRUE(network.ok()) << network.status();
  // This thread (and so the observer's DDS participant) joins the lossy network too: every
  // sample below crossed it, from an agent to the server and from the server back.
  auto inside = (*network)->Enter();
  ASSERT_TRUE(inside.ok()) << inside.status();

  const std::string prefix = ::testing::TempDir() + "/lossy_" + std::to_string(getpid()) + "_";
  std::vector<Robot> robots(3);
  robots[0] = {"alpha", prefix + "alpha.yaml", Pose2{0.0, 0.0, 0.0}, nullptr};
  robots[1] = {"beta", prefix + "beta.yaml", Pose2{30.0, 0.0, 0.0}, nullptr};
  robots[2] = {"gamma", prefix + "gamma.yaml", Pose2{0.0, 30.0, 0.0}, nullptr};
  std::vector<grid::OccupancyGrid> maps = {MakeMap(384, 384), MakeMap(260, 781), MakeMap(300, 300)};
  std::set<TileId> expected_tiles;
  for (size_t i = 0; i < robots.size(); ++i) {
    ASSERT_TRUE(grid::SaveMap(maps[i], robots[i].map_path).ok());
    const std::set<TileId> tiles = KnownTiles(maps[i], robots[i].fleet_from_map);
    expected_tiles.insert(tiles.begin(), tiles.end());
  }

  const std::map<std::string, std::string> env = {
      {"FLEETMAP_DOMAIN", std::to_string(process::RandomDomainId())},
      {"FLEETMAP_LOCALHOST_ONLY", "1"}};  // UDP on loopback: nothing bypasses the loss
  const auto in_network = [&](std::vector<std::string> argv) {
    std::vector<std::string> full = (*network)->ExecPrefix();
    full.insert(full.end(), argv.begin(), argv.end());
    return full;
  };
  Subprocess server(
      in_network({testing::kServerBinary, "--duration", "300", "--map-period", "0.5"}), env);
  ASSERT_TRUE(server.WaitForOutput("listening", kDeadline)) << server.Output();
  for (Robot& robot : robots) {
    const Pose2& pose = robot.fleet_from_map;
    robot.agent = std::make_unique<Subprocess>(
        in_network({testing::kAgentBinary, "--robot-id", robot.name, "--map", robot.map_path,
                    "--fleet-from-map", std::to_string(pose.x), std::to_string(pose.y),
                    std::to_string(pose.yaw)}),
        env);
  }
  const auto soak_end = steady_clock::now() + kSoak;

  transport::ParticipantOptions options;
  options.localhost_only = true;
  options.domain_id = std::stoi(env.at("FLEETMAP_DOMAIN"));
  auto participant = transport::Participant::Create(options);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto fused_tiles =
      transport::VectorTileReader::Create(**participant, transport::kFusedTilesTopic, wake_up);
  ASSERT_TRUE(fused_tiles.ok()) << fused_tiles.status();
  auto fleet_map =
      transport::OccupancyGridReader::Create(**participant, transport::kFleetMapTopic, wake_up);
  ASSERT_TRUE(fleet_map.ok()) << fleet_map.status();

  std::set<TileId> tiles;
  std::optional<grid::OccupancyGrid> fused;
  const auto poll = [&] {
    wake_up->WaitFor(milliseconds(100));
    for (const transport::TileEvent& event : (*fused_tiles)->Drain()) {
      if (event.kind == transport::TileEvent::Kind::kTile) tiles.insert(event.tile.tile);
    }
    for (StatusOr<transport::MapMessage>& map : (*fleet_map)->Drain()) {
      if (map.ok()) fused = std::move(map->grid);
    }
  };
  const auto all_agree = [&] {
    if (!fused) return false;
    for (size_t i = 0; i < robots.size(); ++i) {
      if (Agreement(maps[i], robots[i].fleet_from_map, *fused) <= 0.95) return false;
    }
    return true;
  };

  // Every tile of every robot reaches the fused map, and the fused map shows every robot's map.
  auto deadline = steady_clock::now() + kDeadline;
  while (steady_clock::now() < deadline && !(tiles == expected_tiles && all_agree())) poll();
  EXPECT_EQ(tiles, expected_tiles) << server.Output();
  ASSERT_TRUE(fused.has_value()) << server.Output();
  for (size_t i = 0; i < robots.size(); ++i) {
    EXPECT_GT(Agreement(maps[i], robots[i].fleet_from_map, *fused), 0.95) << robots[i].name;
  }

  // An edit made under loss arrives too: alpha gets a new wall across its map.
  constexpr int kWallRow = 200;
  maps[0] = MakeMap(384, 384, kWallRow);
  ASSERT_TRUE(grid::SaveMap(maps[0], robots[0].map_path).ok());
  deadline = steady_clock::now() + kDeadline;
  const auto wall_arrived = [&] {
    return fused && Agreement(maps[0], robots[0].fleet_from_map, *fused, kWallRow) > 0.95;
  };
  while (steady_clock::now() < deadline && !wall_arrived()) poll();
  EXPECT_TRUE(wall_arrived()) << robots[0].agent->Output();

  // The fleet keeps running under loss; then every robot leaves on purpose, and says so.
  while (steady_clock::now() < soak_end) poll();
  for (Robot& robot : robots) robot.agent->Signal(SIGTERM);
  for (Robot& robot : robots) {
    EXPECT_EQ(robot.agent->Wait(kDeadline), 0) << robot.agent->Output();
    EXPECT_TRUE(server.WaitForOutput("robot " + robot.name + " left", kDeadline))
        << server.Output();
  }
  server.Signal(SIGINT);
  EXPECT_EQ(server.Wait(kDeadline), 0) << server.Output();
  const std::string output = server.Output();
  EXPECT_EQ(Count(output, " lost (no liveliness"), 0u) << output;
  for (const Robot& robot : robots) {
    EXPECT_EQ(Count(output, "robot " + robot.name + " joined"), 1u) << output;
    std::remove(robot.map_path.c_str());
  }
}

}  // namespace
}  // namespace fleetmap
