// A hot standby between real processes (docs/standby.md): two fleetmap-servers fuse the same
// robots; readers take the stronger one's samples. SIGKILL it and the standby serves: the tiles of
// a robot that joins afterwards reach the readers from the standby, rt/fleetmap/map comes from it
// with every wall the killed server had published. Restarted, the stronger server serves again.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>

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
constexpr seconds kDeadline{40};

// A 19 x 19 m map of 6 m rooms whose origin is (x, y) in the fleet frame.
std::string WriteRooms(const std::string& name, double x, double y) {
  grid::OccupancyGrid map(384, 384, 0.05, Pose2{x, y, 0.0}, grid::kFreeValue);
  for (int row = 0; row < map.height(); ++row) {
    for (int col = 0; col < map.width(); ++col) {
      if (col % 120 == 10 || row % 120 == 10) map.at(col, row) = grid::kOccupiedValue;
    }
  }
  const std::string path =
      ::testing::TempDir() + "/standby_" + std::to_string(getpid()) + "_" + name + ".yaml";
  EXPECT_TRUE(grid::SaveMap(map, path).ok());
  return path;
}

using testing::OccupiedCells;

size_t CountIn(const std::set<std::pair<int, int>>& cells, int min_x, int min_y) {
  size_t n = 0;
  for (const auto& [x, y] : cells) n += x >= min_x && y >= min_y;
  return n;
}

class StandbyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    auto participant = testing::LoopbackParticipant(domain_);
    ASSERT_TRUE(participant.ok()) << participant.status();
    participant_ = std::move(participant).value();
    auto maps =
        transport::OccupancyGridReader::Create(*participant_, transport::kFleetMapTopic, wake_up_);
    ASSERT_TRUE(maps.ok()) << maps.status();
    maps_ = std::move(maps).value();
    auto tiles =
        transport::VectorTileReader::Create(*participant_, transport::kFusedTilesTopic, wake_up_);
    ASSERT_TRUE(tiles.ok()) << tiles.status();
    tiles_ = std::move(tiles).value();
    auto servers = transport::FleetServerReader::Create(*participant_, wake_up_);
    ASSERT_TRUE(servers.ok()) << servers.status();
    servers_ = std::move(servers).value();
  }

  void TearDown() override {
    maps_.reset();
    tiles_.reset();
    servers_.reset();
    participant_.reset();
  }

  std::unique_ptr<Subprocess> Start(std::vector<std::string> argv) {
    auto process = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(process->started());
    return process;
  }

  std::unique_ptr<Subprocess> StartServer(const std::string& name, int strength) {
    const std::string store = ::testing::TempDir() + "/standby_" + std::to_string(getpid()) + "_" +
                              std::to_string(domain_) + "_" + name + ".db";
    return Start({testing::kServerBinary, "--duration", "120", "--name", name,
                  "--ownership-strength", std::to_string(strength), "--store", store,
                  "--no-object-learning", "--no-extrapolation"});
  }

  // Drains every reader until `done` says so (or the deadline); keeps the newest of each.
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

  bool Serving(const std::string& name) const {
    const auto it = servers_by_name_.find(name);
    return it != servers_by_name_.end() && it->second.serving;
  }
  // The server's participant id: the first 24 hex digits of its writers' ids.
  std::string IdOf(const std::string& name) const { return servers_by_name_.at(name).server_id; }
  bool TileFrom(int x, int y, const std::string& name) const {
    const auto it = tile_writers_.find({x, y});
    return it != tile_writers_.end() && it->second.rfind(IdOf(name), 0) == 0;
  }
  // What the readers hold, for a failure's message.
  std::string Seen() const {
    std::string out = "map: " + std::to_string(map_ ? OccupiedCells(map_->grid).size() : 0) +
                      " occupied cells; servers:";
    for (const auto& [name, server] : servers_by_name_) {
      out += " " + name + "=" + server.server_id + (server.serving ? " (serving)" : "");
    }
    out += "; fused tiles:";
    for (const auto& [tile, writer] : tile_writers_) {
      out += " (" + std::to_string(tile.first) + "," + std::to_string(tile.second) + ") " + writer;
    }
    return out + "\n";
  }
  size_t MapCellsIn(int min_x, int min_y) const {
    return map_ ? CountIn(OccupiedCells(map_->grid), min_x, min_y) : 0;
  }

  int domain_ = 0;
  std::map<std::string, std::string> env_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::OccupancyGridReader> maps_;
  std::unique_ptr<transport::VectorTileReader> tiles_;
  std::unique_ptr<transport::FleetServerReader> servers_;
  std::optional<transport::MapMessage> map_;
  std::map<std::pair<int, int>, std::string> tile_writers_;  // fused tile -> its last writer
  std::map<std::string, transport::FleetServerMessage> servers_by_name_;
};

TEST_F(StandbyTest, TheStandbyServesWhenTheServerIsKilledAndHandsBackWhenItReturns) {
  // 10 m fused tiles: alpha's rooms are tiles x, y < 2; beta's x >= 4; gamma's y >= 4.
  const std::string west = WriteRooms("west", 0.5, 0.5);
  const std::string east = WriteRooms("east", 40.5, 0.5);
  const std::string north = WriteRooms("north", 0.5, 40.5);
  auto primary = StartServer("primary", 100);
  auto standby = StartServer("standby", 50);
  ASSERT_TRUE(Follow([&] {
    return Serving("primary") && servers_by_name_.count("standby") > 0 && !Serving("standby");
  })) << primary->Output()
      << standby->Output();
  EXPECT_TRUE(standby->WaitForOutput("standing by", kDeadline)) << standby->Output();

  auto alpha = Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", west});
  ASSERT_TRUE(Follow([&] { return MapCellsIn(0, 0) > 3000 && TileFrom(0, 0, "primary"); }))
      << Seen() << primary->Output();
  // Both servers fused alpha; the readers took the primary's samples only.
  ASSERT_TRUE(standby->WaitForOutput("alpha", kDeadline)) << standby->Output();
  const std::set<std::pair<int, int>> alpha_walls = OccupiedCells(map_->grid);

  primary->Signal(SIGKILL);
  primary->Wait(kDeadline);
  auto beta = Start({testing::kAgentBinary, "--robot-id", "beta", "--map", east});
  ASSERT_TRUE(Follow([&] {
    return Serving("standby") && MapCellsIn(800, 0) > 3000 && TileFrom(4, 0, "standby");
  })) << Seen()
      << standby->Output();
  EXPECT_TRUE(standby->WaitForOutput("serving the fleet", kDeadline)) << standby->Output();
  // The standby's map holds every wall the killed server had published.
  const std::set<std::pair<int, int>> after_failover = OccupiedCells(map_->grid);
  size_t lost = 0;
  for (const auto& cell : alpha_walls) lost += after_failover.count(cell) == 0;
  EXPECT_EQ(lost, 0u) << "of " << alpha_walls.size() << " walls";

  // The primary returns (a new participant on its store): it serves again, the standby stands by.
  servers_by_name_.erase("primary");
  auto returned = StartServer("primary", 100);
  ASSERT_TRUE(Follow([&] { return Serving("primary") && !Serving("standby"); }))
      << Seen() << returned->Output() << standby->Output();
  auto gamma = Start({testing::kAgentBinary, "--robot-id", "gamma", "--map", north});
  ASSERT_TRUE(Follow([&] { return MapCellsIn(0, 800) > 3000 && TileFrom(0, 4, "primary"); }))
      << returned->Output();
  EXPECT_GT(MapCellsIn(800, 0), 3000u) << "beta's rooms, fused while the primary was down";

  returned->Signal(SIGINT);
  EXPECT_EQ(returned->Wait(kDeadline), 0) << returned->Output();
  standby->Signal(SIGINT);
  EXPECT_EQ(standby->Wait(kDeadline), 0) << standby->Output();
}

}  // namespace
}  // namespace fleetmap
