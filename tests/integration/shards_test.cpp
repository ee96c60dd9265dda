// The fleet map sharded by region between real processes (docs/shards.md): two shard servers read
// only their region's robot tiles (a content filter the agents' writers evaluate), an aggregator
// joins their grids into rt/fleetmap/map, and that grid is the one a single server fusing the same
// robots publishes, cell for cell, with a robot whose map crosses the border between the shards.
// A robot mapping where no shard's region lies is reported by the shards, not dropped silently.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/core/wake_up.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/loopback_participant.hpp"
#include "tests/integration/occupied_cells.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;

// Bounds on waits for a loaded 2-core machine, not assertions about time.
constexpr seconds kDeadline{60};

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/shards_" + std::to_string(getpid()) + "_" + name;
}

// A 19 x 19 m map of 6 m rooms whose origin is (x, y) in the fleet frame.
std::string WriteRooms(const std::string& name, double x, double y) {
  grid::OccupancyGrid map(384, 384, 0.05, Pose2{x, y, 0.0}, grid::kFreeValue);
  for (int row = 0; row < map.height(); ++row) {
    for (int col = 0; col < map.width(); ++col) {
      if (col % 120 == 10 || row % 120 == 10) map.at(col, row) = grid::kOccupiedValue;
    }
  }
  const std::string path = TempPath(name + ".yaml");
  EXPECT_TRUE(grid::SaveMap(map, path).ok());
  return path;
}

// One DDS domain's fleet, as a reader sees it: rt/fleetmap/map, and who wrote each fused tile.
class FleetOnDomain {
 public:
  explicit FleetOnDomain(int domain) : domain_(domain) {
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    auto participant = testing::LoopbackParticipant(domain);
    EXPECT_TRUE(participant.ok()) << participant.status();
    participant_ = std::move(participant).value();
    maps_ =
        transport::OccupancyGridReader::Create(*participant_, transport::kFleetMapTopic, wake_up_)
            .value();
    tiles_ =
        transport::VectorTileReader::Create(*participant_, transport::kFusedTilesTopic, wake_up_)
            .value();
    servers_ = transport::FleetServerReader::Create(*participant_, wake_up_).value();
  }
  ~FleetOnDomain() {
    for (auto& process : processes_) process->Signal(SIGINT);
    for (auto& process : processes_) process->Wait(kDeadline);
    maps_.reset();
    tiles_.reset();
    servers_.reset();
    participant_.reset();
  }

  Subprocess& Start(std::vector<std::string> argv) {
    processes_.push_back(std::make_unique<Subprocess>(std::move(argv), env_));
    EXPECT_TRUE(processes_.back()->started());
    return *processes_.back();
  }

  // Drains the readers until `done` (or the deadline).
  bool Follow(const std::function<bool()>& done) {
    const auto until = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < until) {
      wake_up_->WaitFor(milliseconds(100));
      for (StatusOr<transport::MapMessage>& map : maps_->Drain()) {
        if (map.ok()) map_ = std::move(map).value();
      }
      for (transport::TileEvent& event : tiles_->Drain()) {
        if (event.kind == transport::TileEvent::Kind::kTile) {
          tile_writers_[{event.tile.tile.x, event.tile.tile.y}] = event.writer;
        }
      }
      for (transport::FleetServerEvent& event : servers_->Drain()) {
        if (event.kind == transport::FleetServerEvent::Kind::kSample) {
          servers_by_name_[event.message.name] = event.message;
        }
      }
      if (done()) return true;
    }
    return false;
  }

  size_t OccupiedCells() const { return map_ ? testing::OccupiedCells(map_->grid).size() : 0; }
  const std::optional<transport::MapMessage>& map() const { return map_; }
  // The name of the server whose participant wrote the fused tile (x, y); empty when none did.
  std::string TileWriter(int x, int y) const {
    const auto tile = tile_writers_.find({x, y});
    if (tile == tile_writers_.end()) return {};
    for (const auto& [name, server] : servers_by_name_) {
      if (tile->second.rfind(server.server_id, 0) == 0) return name;
    }
    return "?";
  }
  const std::map<std::string, transport::FleetServerMessage>& servers() const {
    return servers_by_name_;
  }
  std::string Seen() const {
    std::string out = "map: " + std::to_string(OccupiedCells()) + " occupied cells; tiles:";
    for (const auto& [tile, writer] : tile_writers_) {
      out += " (" + std::to_string(tile.first) + "," + std::to_string(tile.second) + ") " +
             TileWriter(tile.first, tile.second);
    }
    return out + "\n";
  }

 private:
  int domain_;
  std::map<std::string, std::string> env_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::OccupancyGridReader> maps_;
  std::unique_ptr<transport::VectorTileReader> tiles_;
  std::unique_ptr<transport::FleetServerReader> servers_;
  std::optional<transport::MapMessage> map_;
  std::map<std::pair<int, int>, std::string> tile_writers_;
  std::map<std::string, transport::FleetServerMessage> servers_by_name_;
  std::vector<std::unique_ptr<Subprocess>> processes_;
};

std::vector<std::string> Server(const std::string& name, std::vector<std::string> more = {}) {
  std::vector<std::string> argv = {
      testing::kServerBinary, "--duration",        "150", "--name", name,
      "--no-object-learning", "--no-extrapolation"};
  argv.insert(argv.end(), more.begin(), more.end());
  return argv;
}

TEST(ShardsTest, TwoShardsAndTheAggregatorPublishTheMapOneServerPublishes) {
  // 10 m fused tiles: west holds tile columns 0-2, east 3-5. alpha maps x 0.5-19.7 m (west only),
  // beta x 20.5-39.7 m (across the border at 30 m), gamma x 70.5-89.7 m (no shard's region).
  const std::string shards = TempPath("shards.yaml");
  std::ofstream(shards) << "shards:\n  west: [0, 0, 30, 60]\n  east: [30, 0, 60, 60]\n";
  const std::string alpha_map = WriteRooms("alpha", 0.5, 0.5);
  const std::string beta_map = WriteRooms("beta", 20.5, 0.5);
  const std::string gamma_map = WriteRooms("gamma", 70.5, 0.5);

  const int sharded_domain = RandomDomainId();
  int single_domain = RandomDomainId();
  while (single_domain == sharded_domain) single_domain = RandomDomainId();
  FleetOnDomain sharded(sharded_domain);
  FleetOnDomain single(single_domain);

  // Different strengths: were west to write an east tile, a reader would take west's.
  Subprocess& west = sharded.Start(
      Server("west", {"--shards", shards, "--shard", "west", "--ownership-strength", "100"}));
  Subprocess& east = sharded.Start(
      Server("east", {"--shards", shards, "--shard", "east", "--ownership-strength", "50"}));
  Subprocess& aggregator = sharded.Start(
      {testing::kServerBinary, "--duration", "150", "--aggregate", "--shards", shards});
  single.Start(Server("single"));
  ASSERT_TRUE(sharded.Follow([&] { return sharded.servers().size() == 2; }))
      << west.Output() << east.Output();
  // Each shard serves its own region: neither stands by for the other.
  ASSERT_TRUE(sharded.Follow([&] {
    return sharded.servers().at("west").serving && sharded.servers().at("east").serving;
  })) << west.Output()
      << east.Output();

  for (FleetOnDomain* fleet : {&sharded, &single}) {
    fleet->Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", alpha_map});
    fleet->Start({testing::kAgentBinary, "--robot-id", "beta", "--map", beta_map});
  }
  sharded.Start({testing::kAgentBinary, "--robot-id", "gamma", "--map", gamma_map});

  // Both robots' walls in both fleets' maps, beta's on both sides of the border.
  const auto whole = [](const FleetOnDomain& fleet) {
    return fleet.map() && fleet.TileWriter(0, 0) != "" && fleet.TileWriter(3, 1) != "" &&
           fleet.OccupiedCells() > 5500;
  };
  ASSERT_TRUE(single.Follow([&] { return whole(single); })) << single.Seen();
  ASSERT_TRUE(sharded.Follow([&] { return whole(sharded); }))
      << sharded.Seen() << west.Output() << east.Output() << aggregator.Output();

  // Every fused tile came from the shard whose region holds it.
  for (int x = 0; x <= 3; ++x) {
    for (int y = 0; y <= 1; ++y) {
      EXPECT_EQ(sharded.TileWriter(x, y), x <= 2 ? "west" : "east") << sharded.Seen();
    }
  }
  // Let both maps settle on the same inputs, then compare them cell for cell.
  const auto same = [&] {
    return sharded.map() && single.map() &&
           sharded.map()->grid.origin().x == single.map()->grid.origin().x &&
           sharded.map()->grid.origin().y == single.map()->grid.origin().y &&
           sharded.map()->grid.data() == single.map()->grid.data();
  };
  bool equal = false;
  for (int round = 0; round < 30 && !equal; ++round) {
    single.Follow([] { return true; });
    sharded.Follow([] { return true; });
    equal = same();
    if (!equal) std::this_thread::sleep_for(milliseconds(500));
  }
  ASSERT_TRUE(sharded.map() && single.map());
  EXPECT_TRUE(equal) << "sharded " << sharded.map()->grid.width() << "x"
                     << sharded.map()->grid.height() << " at (" << sharded.map()->grid.origin().x
                     << ", " << sharded.map()->grid.origin().y << "), " << sharded.OccupiedCells()
                     << " occupied; single " << single.map()->grid.width() << "x"
                     << single.map()->grid.height() << " at (" << single.map()->grid.origin().x
                     << ", " << single.map()->grid.origin().y << "), " << single.OccupiedCells()
                     << " occupied";
  // gamma's tiles lie on no shard's region: each shard says so, naming it.
  EXPECT_TRUE(west.WaitForOutput("of robot gamma lies on no shard's region", kDeadline))
      << west.Output();
  EXPECT_TRUE(east.WaitForOutput("of robot gamma lies on no shard's region", kDeadline))
      << east.Output();
  EXPECT_TRUE(sharded.TileWriter(7, 0).empty()) << sharded.Seen();

  // The agents' writers filtered: no shard received a tile of the other's region.
  for (Subprocess* shard : {&west, &east}) {
    shard->Signal(SIGINT);
    EXPECT_EQ(shard->Wait(kDeadline), std::optional<int>(0)) << shard->Output();
    EXPECT_NE(shard->Output().find(" 0 tiles of other shards received"), std::string::npos)
        << shard->Output();
  }
}

TEST(ShardsTest, BadShardOptionsExitTwoNamingTheProblem) {
  const std::string overlapping = TempPath("overlap.yaml");
  std::ofstream(overlapping) << "shards:\n  west: [0, 0, 30, 60]\n  east: [20, 0, 60, 60]\n";
  const std::string good = TempPath("good.yaml");
  std::ofstream(good) << "shards:\n  west: [0, 0, 30, 60]\n  east: [30, 0, 60, 60]\n";
  const std::map<std::string, std::string> env = {
      {"FLEETMAP_DOMAIN", std::to_string(RandomDomainId())}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--shards", overlapping, "--shard", "west"}, "shards west and east overlap"},
      {{"--shards", good, "--shard", "north"}, "--shard north is not in"},
      {{"--region", "0", "0", "30", "60"}, "--region needs --shard"},
      {{"--shard", "west"}, "needs --region X0 Y0 X1 Y1 or --shards"},
      {{"--shard", "west", "--region", "30", "0", "0", "60"}, "has no area"},
      {{"--aggregate"}, "--aggregate needs --shards"},
      {{"--shards", TempPath("missing.yaml"), "--shard", "west"}, "no such file"},
  };
  for (const auto& [arguments, message] : cases) {
    std::vector<std::string> argv = {testing::kServerBinary, "--duration", "5"};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    Subprocess server(argv, env);
    EXPECT_EQ(server.Wait(kDeadline), std::optional<int>(2)) << message << "\n" << server.Output();
    EXPECT_NE(server.Output().find(message), std::string::npos) << server.Output();
  }
}

// The cells [x0, x0 + w) of every row of `g`, as a map with its corner at `origin`.
grid::OccupancyGrid Columns(const grid::OccupancyGrid& g, int x0, int w, const Pose2& origin) {
  grid::OccupancyGrid out(w, g.height(), g.resolution(), origin);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < w; ++x) out.at(x, y) = g.at(x0 + x, y);
  }
  return out;
}

// A robot at an unknown pose whose map spans two shards: its home shard (east, where the fleet
// map it overlaps lies) places it by registration and alone writes its robot_frames row; the
// other shard (west) follows that row and fuses the part of the robot's map in its region.
TEST(ShardsTest, ARobotAtAnUnknownPoseIsPlacedByItsHomeShardAndFollowedByTheOther) {
  const auto house =
      grid::LoadMap(std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml");
  ASSERT_TRUE(house.ok()) << house.status();
  // alpha maps the right 60 % of the house at x 40 m on (east's tiles 4 and up), its frame
  // given; beta the left 60 %, in a frame of its own, truly at x 32-44 m: tile 3 is west's.
  const grid::OccupancyGrid& g = house->grid;
  const int w = g.width() * 3 / 5;
  const Pose2 alpha_origin{40.0, 7.5, 0.0};
  const std::string alpha_map = TempPath("house_alpha.yaml");
  ASSERT_TRUE(grid::SaveMap(Columns(g, g.width() - w, w, alpha_origin), alpha_map).ok());
  const std::string beta_map = TempPath("house_beta.yaml");
  ASSERT_TRUE(grid::SaveMap(Columns(g, 0, w, Pose2{-70.0, 15.0, 0.0}), beta_map).ok());
  const std::string shards = TempPath("homes.yaml");
  std::ofstream(shards) << "shards:\n  west: [-1000, -1000, 40, 1000]\n"
                           "  east: [40, -1000, 1000, 1000]\nrobots:\n  beta: east\n";

  FleetOnDomain fleet(RandomDomainId());
  Subprocess& west = fleet.Start(Server("west", {"--shards", shards, "--shard", "west"}));
  Subprocess& east = fleet.Start(Server("east", {"--shards", shards, "--shard", "east"}));
  ASSERT_TRUE(fleet.Follow([&] { return fleet.servers().size() == 2; })) << west.Output();
  fleet.Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", alpha_map, "--fleet-from-map",
               "0", "0", "0"});
  ASSERT_TRUE(fleet.Follow([&] { return fleet.TileWriter(4, 1) == "east"; }))
      << fleet.Seen() << east.Output();
  fleet.Start({testing::kAgentBinary, "--robot-id", "beta", "--map", beta_map, "--unplaced"});

  // West fuses beta's part once east placed beta: a fused tile of column 3 only beta maps.
  const auto west_has_beta = [&] {
    for (int y = 0; y <= 2; ++y) {
      if (fleet.TileWriter(3, y) == "west") return true;
    }
    return false;
  };
  ASSERT_TRUE(fleet.Follow(west_has_beta)) << fleet.Seen() << east.Output() << west.Output();
  EXPECT_TRUE(east.WaitForOutput("robot beta placed", kDeadline)) << east.Output();
  EXPECT_EQ(west.Output().find("robot beta placed"), std::string::npos)
      << "only the home shard registers beta:\n"
      << west.Output();
}

}  // namespace
}  // namespace fleetmap
