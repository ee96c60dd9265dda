// DDS on UDP loopback between real processes: fleetmap-agent and fleetmap-server binaries, and
// readers/writers in this test process with intra-process delivery off. Each test uses its own
// random domain so parallel runs never meet.

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/store/map_store.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "common/transport/tile_payload.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/map_agreement.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string& kAgent = testing::kAgentBinary;
const std::string& kServer = testing::kServerBinary;
// Generous deadlines for a loaded 2-core CI machine; they bound waits, they are not assertions.
constexpr seconds kDeadline{20};

// A synthetic map written with map_server's format: rooms of walls with a few unknown patches.
// Large enough (hundreds of KB) that every sample is fragmented over UDP.
std::string WriteMap(const std::string& name, int width, int height) {
  grid::OccupancyGrid map(width, height, 0.05, Pose2{-3.0, 1.5, 0.0}, grid::kFreeValue);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (x % 40 == 0 || y % 30 == 0) map.at(x, y) = grid::kOccupiedValue;
      if ((x / 7 + y / 5) % 11 == 0) map.at(x, y) = grid::kUnknownValue;
    }
  }
  const std::string path =
      ::testing::TempDir() + "/fleet_dds_" + std::to_string(getpid()) + "_" + name + ".yaml";
  const Status saved = grid::SaveMap(map, path);
  EXPECT_TRUE(saved.ok()) << saved;
  return path;
}

// Removes a map WriteMap wrote: its YAML and the image beside it.
void RemoveMap(const std::string& yaml_path) {
  std::error_code ignored;
  std::filesystem::remove(yaml_path, ignored);
  std::filesystem::remove(std::filesystem::path(yaml_path).replace_extension(".pgm"), ignored);
}

// A map for one test, removed when the test ends (ctest runs each case in a process of its own,
// so the maps were left in the temp directory once per case and run).
class TestMap {
 public:
  TestMap(const std::string& name, int width, int height) : path_(WriteMap(name, width, height)) {}
  ~TestMap() { RemoveMap(path_); }
  TestMap(const TestMap&) = delete;
  TestMap& operator=(const TestMap&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class FleetDdsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    map_path_ = WriteMap("small", 384, 384);
    tall_map_path_ = WriteMap("tall", 260, 781);
  }
  static void TearDownTestSuite() {
    RemoveMap(map_path_);
    RemoveMap(tall_map_path_);
  }

  void SetUp() override {
    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  }

  static inline std::string map_path_;
  static inline std::string tall_map_path_;

  std::unique_ptr<transport::Participant> MakeParticipant() {
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;  // exercise serialization and UDP, even in-process
    auto participant = transport::Participant::Create(options);
    EXPECT_TRUE(participant.ok()) << participant.status();
    return participant.ok() ? std::move(participant).value() : nullptr;
  }

  std::unique_ptr<Subprocess> StartAgent(const std::string& robot, const std::string& map,
                                         std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {kAgent, "--robot-id", robot, "--map", map};
    argv.insert(argv.end(), extra.begin(), extra.end());
    auto agent = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(agent->started());
    return agent;
  }

  // Waits for the first event of `kind` about `robot`, draining the reader.
  static bool WaitForEvent(transport::RobotStatusReader& reader, WakeUp& wake_up,
                           const std::string& robot, transport::RobotEvent::Kind kind,
                           std::vector<transport::RobotEvent>* seen = nullptr) {
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up.WaitFor(milliseconds(100));
      for (const transport::RobotEvent& event : reader.Drain()) {
        if (seen != nullptr) seen->push_back(event);
        if (event.robot.value == robot && event.kind == kind) return true;
      }
    }
    return false;
  }

  static std::optional<transport::MapMessage> WaitForMap(transport::OccupancyGridReader& reader,
                                                         WakeUp& wake_up) {
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up.WaitFor(milliseconds(100));
      for (StatusOr<transport::MapMessage>& map : reader.Drain()) {
        EXPECT_TRUE(map.ok()) << map.status();
        if (map.ok()) return std::move(map).value();
      }
    }
    return std::nullopt;
  }

  // Expects the server's fused grid on rt/fleetmap/map to come to agree with the map at
  // `map_path` (placed at the fleet origin) on more than 95 % of its known cells.
  void ExpectFleetMapShowsMap(const std::string& map_path, const Subprocess& server);

  int domain_ = 0;
  std::map<std::string, std::string> env_;
};

TEST_F(FleetDdsTest, AgentMapCrossesToAnotherProcessCellForCell) {
  auto agent = StartAgent("alpha", map_path_, {"--wire", "grid"});
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::OccupancyGridReader::Create(
      *participant, transport::RobotMapTopic(RobotId{"alpha"}), wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  const std::optional<transport::MapMessage> received = WaitForMap(**reader, *wake_up);
  ASSERT_TRUE(received.has_value()) << agent->Output();

  const auto expected = grid::LoadMap(map_path_);
  ASSERT_TRUE(expected.ok()) << expected.status();
  EXPECT_EQ(received->frame_id, "alpha/map");
  EXPECT_EQ(received->grid.width(), expected->grid.width());
  EXPECT_EQ(received->grid.height(), expected->grid.height());
  EXPECT_FLOAT_EQ(received->grid.resolution(), expected->grid.resolution());
  EXPECT_NEAR(received->grid.origin().x, expected->grid.origin().x, 1e-9);
  EXPECT_NEAR(received->grid.origin().y, expected->grid.origin().y, 1e-9);
  EXPECT_EQ(received->grid.data(), expected->grid.data());
  EXPECT_GT(received->serialized_bytes, received->grid.data().size());
}

TEST_F(FleetDdsTest, LateJoiningReaderReceivesTransientLocalMap) {
  auto agent = StartAgent("late", map_path_, {"--wire", "grid"});
  ASSERT_TRUE(agent->WaitForOutput("in the fleet", kDeadline)) << agent->Output();
  // The map was published before this reader existed: durability must deliver it.
  std::this_thread::sleep_for(milliseconds(500));
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::OccupancyGridReader::Create(
      *participant, transport::RobotMapTopic(RobotId{"late"}), wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();
  const auto received = WaitForMap(**reader, *wake_up);
  ASSERT_TRUE(received.has_value()) << agent->Output();
  EXPECT_EQ(received->grid.cell_count(), 384 * 384);
}

TEST_F(FleetDdsTest, FiftyRobotsAllArrive) {
  auto writer_side = MakeParticipant();
  auto reader_side = MakeParticipant();
  ASSERT_NE(writer_side, nullptr);
  ASSERT_NE(reader_side, nullptr);
  auto writer = transport::RobotStatusWriter::Create(*writer_side);
  ASSERT_TRUE(writer.ok()) << writer.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RobotStatusReader::Create(*reader_side, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  constexpr int kRobots = 50;
  for (int i = 0; i < kRobots; ++i) {
    RobotStatus status;
    status.robot = RobotId{"robot_" + std::to_string(i)};
    status.map_width = static_cast<uint32_t>(i);
    ASSERT_TRUE((*writer)->Write(status).ok());
  }

  std::set<std::string> seen;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (seen.size() < kRobots && std::chrono::steady_clock::now() < deadline) {
    wake_up->WaitFor(milliseconds(100));
    for (const transport::RobotEvent& event : (*reader)->Drain()) {
      ASSERT_EQ(event.kind, transport::RobotEvent::Kind::kStatus);
      EXPECT_EQ(event.robot.value, "robot_" + std::to_string(event.status.map_width));
      seen.insert(event.robot.value);
    }
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(kRobots));
}

TEST_F(FleetDdsTest, KilledAgentIsReportedLostWhileOthersLive) {
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RobotStatusReader::Create(*participant, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  // A live neighbour must not keep the dead robot alive (it did with AUTOMATIC liveliness).
  auto survivor = StartAgent("survivor", map_path_);
  auto doomed = StartAgent("doomed", map_path_);
  std::vector<transport::RobotEvent> seen;
  ASSERT_TRUE(
      WaitForEvent(**reader, *wake_up, "survivor", transport::RobotEvent::Kind::kStatus, &seen));
  ASSERT_TRUE(WaitForEvent(**reader, *wake_up, "doomed", transport::RobotEvent::Kind::kStatus))
      << doomed->Output();
  doomed->Signal(SIGKILL);
  seen.clear();
  EXPECT_TRUE(
      WaitForEvent(**reader, *wake_up, "doomed", transport::RobotEvent::Kind::kLost, &seen));
  for (const auto& event : seen) {
    EXPECT_NE(event.kind, transport::RobotEvent::Kind::kLeft);
    if (event.robot.value == "survivor") {
      EXPECT_EQ(event.kind, transport::RobotEvent::Kind::kStatus);
    }
  }
}

TEST_F(FleetDdsTest, StoppedAgentLeavesOnPurpose) {
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader = transport::RobotStatusReader::Create(*participant, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  auto agent = StartAgent("polite", map_path_);
  ASSERT_TRUE(WaitForEvent(**reader, *wake_up, "polite", transport::RobotEvent::Kind::kStatus));
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->Wait(kDeadline), 0) << agent->Output();
  EXPECT_TRUE(WaitForEvent(**reader, *wake_up, "polite", transport::RobotEvent::Kind::kLeft));
}

TEST_F(FleetDdsTest, ServerFollowsRobotsJoiningSendingAndDying) {
  Subprocess server({kServer, "--duration", "60"}, env_);
  ASSERT_TRUE(server.WaitForOutput("listening", kDeadline)) << server.Output();
  auto alpha = StartAgent("alpha", map_path_);
  auto beta = StartAgent("beta", tall_map_path_, {"--wire", "grid"});

  EXPECT_TRUE(server.WaitForOutput("robot alpha joined (tiles wire", kDeadline)) << server.Output();
  EXPECT_TRUE(server.WaitForOutput("robot beta joined (grid wire", kDeadline)) << server.Output();
  EXPECT_TRUE(server.WaitForOutput("map from beta: 260 x 781 cells", kDeadline)) << server.Output();

  beta->Signal(SIGKILL);
  EXPECT_TRUE(server.WaitForOutput("robot beta lost", kDeadline)) << server.Output();
  alpha->Signal(SIGTERM);
  EXPECT_TRUE(server.WaitForOutput("robot alpha left", kDeadline)) << server.Output();

  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  const std::string output = server.Output();
  EXPECT_NE(output.find("alpha            left"), std::string::npos) << output;
  EXPECT_NE(output.find("beta             lost"), std::string::npos) << output;
}

// Reads rt/fleetmap/map until a grid satisfies `done` (the fused map fills in as tiles arrive);
// returns the last grid received.
std::optional<transport::MapMessage> WaitForFleetMap(
    transport::Participant& participant,
    const std::function<bool(const transport::MapMessage&)>& done) {
  auto wake_up = std::make_shared<WakeUp>();
  auto reader =
      transport::OccupancyGridReader::Create(participant, transport::kFleetMapTopic, wake_up);
  EXPECT_TRUE(reader.ok()) << reader.status();
  if (!reader.ok()) return std::nullopt;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  std::optional<transport::MapMessage> newest;
  while (std::chrono::steady_clock::now() < deadline) {
    wake_up->WaitFor(milliseconds(100));
    for (auto& map : (*reader)->Drain()) {
      if (map.ok()) newest = std::move(map).value();
    }
    if (newest && done(*newest)) break;
  }
  return newest;
}

// testing::Agreement with the robot's map placed by a pose.
double Agreement(const grid::OccupancyGrid& source, const Pose2& fleet_from_map,
                 const grid::OccupancyGrid& fused) {
  return testing::Agreement(source, fleet_from_map.ToTransform(), fused);
}

void FleetDdsTest::ExpectFleetMapShowsMap(const std::string& map_path, const Subprocess& server) {
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  const auto expected = grid::LoadMap(map_path);
  ASSERT_TRUE(expected.ok()) << expected.status();
  const auto fleet_map = WaitForFleetMap(*participant, [&](const transport::MapMessage& map) {
    return Agreement(expected->grid, Pose2{}, map.grid) > 0.95;
  });
  ASSERT_TRUE(fleet_map.has_value()) << server.Output();
  EXPECT_GT(Agreement(expected->grid, Pose2{}, fleet_map->grid), 0.95);
}

TEST_F(FleetDdsTest, TilesAreFusedAndRedistributed) {
  Subprocess server({kServer, "--duration", "60"}, env_);
  auto alpha = StartAgent("alpha", map_path_);
  auto beta = StartAgent("beta", tall_map_path_, {"--fleet-from-map", "30", "0", "0"});
  ASSERT_TRUE(alpha->WaitForOutput("changed tiles", kDeadline)) << alpha->Output();

  // A reader that joins late still gets every fused tile (transient local).
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto fused =
      transport::VectorTileReader::Create(*participant, transport::kFusedTilesTopic, wake_up);
  ASSERT_TRUE(fused.ok()) << fused.status();
  std::set<TileId> tiles;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  // alpha spans tiles x -1..1, y 0..2 (9); beta x 2..3, y 0..4 (10).
  while (std::chrono::steady_clock::now() < deadline && tiles.size() < 19) {
    wake_up->WaitFor(milliseconds(100));
    for (const auto& event : (*fused)->Drain()) {
      ASSERT_NE(event.kind, transport::TileEvent::Kind::kRejected) << event.error;
      if (event.kind == transport::TileEvent::Kind::kTile) {
        EXPECT_EQ(event.tile.robot_id.value, "fleet");
        // The writer's host, learned from discovery (what the server's per-host budget charges).
        EXPECT_EQ(event.host, "127.0.0.1");
        tiles.insert(event.tile.tile);
      }
    }
  }
  EXPECT_EQ(tiles.size(), 19u) << server.Output();

  // The fused grid on rt/fleetmap/map comes to agree with both robots' maps where they know
  // something.
  const auto alpha_map = grid::LoadMap(map_path_);
  const auto beta_map = grid::LoadMap(tall_map_path_);
  ASSERT_TRUE(alpha_map.ok() && beta_map.ok());
  const auto both_agree = [&](const transport::MapMessage& map) {
    return Agreement(alpha_map->grid, Pose2{}, map.grid) > 0.95 &&
           Agreement(beta_map->grid, Pose2{30.0, 0.0, 0.0}, map.grid) > 0.95;
  };
  const auto fleet_map = WaitForFleetMap(*participant, both_agree);
  ASSERT_TRUE(fleet_map.has_value()) << server.Output();
  EXPECT_EQ(fleet_map->frame_id, "fleet");
  EXPECT_GT(Agreement(alpha_map->grid, Pose2{}, fleet_map->grid), 0.95);
  EXPECT_GT(Agreement(beta_map->grid, Pose2{30.0, 0.0, 0.0}, fleet_map->grid), 0.95);
}

// Share of `cells` (map-frame cell indices of `source`) that `fused` shows occupied.
double OccupiedShare(const grid::OccupancyGrid& source, const Pose2& fleet_from_map,
                     const std::vector<grid::CellIndex>& cells, const grid::OccupancyGrid& fused) {
  int64_t occupied = 0;
  for (const grid::CellIndex& index : cells) {
    const auto cell =
        fused.CellAt(fleet_from_map.ToTransform() * source.CellCenter(index.x, index.y));
    if (cell && fused.StateAt(cell->x, cell->y) == grid::CellState::kOccupied) ++occupied;
  }
  return cells.empty() ? 0.0 : static_cast<double>(occupied) / cells.size();
}

// The two ROS-native patch wires for real: each agent sends its whole map once, then only
// patches of the tiles that change (raw on one robot, zstd on the other); the server applies
// them to each robot's grid and the fused map shows the change.
TEST_F(FleetDdsTest, PatchWiresCarryMapChangesIntoTheFusedMap) {
  const TestMap alpha_map("patch_alpha", 384, 384);
  const TestMap beta_map("patch_beta", 384, 384);
  const std::string& alpha_path = alpha_map.path();
  const std::string& beta_path = beta_map.path();
  Subprocess server({kServer, "--duration", "90", "--map-period", "0.2"}, env_);
  auto alpha = StartAgent("alpha", alpha_path, {"--wire", "grid-updates"});
  auto beta = StartAgent("beta", beta_path,
                         {"--wire", "grid-updates-zstd", "--fleet-from-map", "30", "0", "0"});
  ASSERT_TRUE(server.WaitForOutput("robot alpha joined (grid-updates wire", kDeadline))
      << server.Output();
  ASSERT_TRUE(server.WaitForOutput("robot beta joined (grid-updates-zstd wire", kDeadline))
      << server.Output();
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);

  // A new wall, 6 cells thick, where both maps were free: written into the map files, which the
  // agents follow.
  std::vector<grid::CellIndex> wall;
  for (int y = 200; y < 206; ++y) {
    for (int x = 101; x < 139; ++x) wall.push_back(grid::CellIndex{x, y});
  }
  auto changed = grid::LoadMap(alpha_path);
  ASSERT_TRUE(changed.ok()) << changed.status();
  for (const grid::CellIndex& cell : wall) changed->grid.at(cell.x, cell.y) = grid::kOccupiedValue;
  const Pose2 beta_place{30.0, 0.0, 0.0};
  // Before the change, the fused map shows both maps and no wall.
  const auto before = WaitForFleetMap(*participant, [&](const transport::MapMessage& map) {
    return Agreement(changed->grid, Pose2{}, map.grid) > 0.9 &&
           Agreement(changed->grid, beta_place, map.grid) > 0.9;
  });
  ASSERT_TRUE(before.has_value()) << server.Output();
  ASSERT_LT(OccupiedShare(changed->grid, Pose2{}, wall, before->grid), 0.3);

  ASSERT_TRUE(grid::SaveMap(changed->grid, alpha_path).ok());
  ASSERT_TRUE(grid::SaveMap(changed->grid, beta_path).ok());
  const auto after = WaitForFleetMap(*participant, [&](const transport::MapMessage& map) {
    return OccupiedShare(changed->grid, Pose2{}, wall, map.grid) > 0.8 &&
           OccupiedShare(changed->grid, beta_place, wall, map.grid) > 0.8;
  });
  ASSERT_TRUE(after.has_value()) << server.Output();
  // Vectorizing rounds the new wall's ends (epsilon): most of its cells, not all, read occupied.
  EXPECT_GT(OccupiedShare(changed->grid, Pose2{}, wall, after->grid), 0.8) << server.Output();
  EXPECT_GT(OccupiedShare(changed->grid, beta_place, wall, after->grid), 0.8) << server.Output();
  EXPECT_GT(Agreement(changed->grid, Pose2{}, after->grid), 0.95);
  EXPECT_GT(Agreement(changed->grid, beta_place, after->grid), 0.95);

  // The change went as patches of the one tile it touched, not as a whole grid.
  EXPECT_TRUE(alpha->WaitForOutput("as 1 patches", kDeadline)) << alpha->Output();
  EXPECT_TRUE(beta->WaitForOutput("as 1 patches", kDeadline)) << beta->Output();
  EXPECT_NE(server.Output().find("1 updates"), std::string::npos) << server.Output();
  alpha->Signal(SIGTERM);
  beta->Signal(SIGTERM);
  EXPECT_EQ(alpha->Wait(kDeadline), 0) << alpha->Output();
  EXPECT_EQ(beta->Wait(kDeadline), 0) << beta->Output();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_EQ(server.Output().find("(malformed)"), std::string::npos) << server.Output();
}

TEST_F(FleetDdsTest, KilledAgentsTilesStayInTheFusedMap) {
  Subprocess server({kServer, "--duration", "60"}, env_);
  auto alpha = StartAgent("alpha", map_path_);
  ASSERT_TRUE(alpha->WaitForOutput("changed tiles", kDeadline)) << alpha->Output();
  ASSERT_TRUE(server.WaitForOutput("robot alpha joined", kDeadline)) << server.Output();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  alpha->Signal(SIGKILL);
  ASSERT_TRUE(server.WaitForOutput("robot alpha lost", kDeadline)) << server.Output();

  // A reader that arrives after the robot died still gets its part of the map.
  ExpectFleetMapShowsMap(map_path_, server);
}

TEST_F(FleetDdsTest, ServerPlacesGridRobotsWithItsTransformsFile) {
  const std::string transforms = ::testing::TempDir() + "/transforms_" + std::to_string(getpid()) +
                                 "_" + std::to_string(domain_) + ".yaml";
  std::ofstream(transforms) << "robots:\n  alpha: [30.0, 0.0, 0.0]\n";
  Subprocess server({kServer, "--duration", "60", "--transforms", transforms}, env_);
  // The agent says nothing about where its map is: the server's file places it.
  auto alpha = StartAgent("alpha", map_path_, {"--wire", "grid"});
  auto participant = MakeParticipant();
  ASSERT_NE(participant, nullptr);
  const auto expected = grid::LoadMap(map_path_);
  ASSERT_TRUE(expected.ok());
  const auto fleet_map = WaitForFleetMap(*participant, [&](const transport::MapMessage& map) {
    return Agreement(expected->grid, Pose2{30.0, 0.0, 0.0}, map.grid) > 0.95;
  });
  ASSERT_TRUE(fleet_map.has_value()) << server.Output();
  EXPECT_GT(Agreement(expected->grid, Pose2{30.0, 0.0, 0.0}, fleet_map->grid), 0.95);
  std::remove(transforms.c_str());
}

TEST_F(FleetDdsTest, AnAgentWhoseRobotIdIsTakenIsToldAndExits) {
  Subprocess server({kServer, "--duration", "60"}, env_);
  auto first = StartAgent("twin", map_path_);
  ASSERT_TRUE(server.WaitForOutput("robot twin joined", kDeadline)) << server.Output();
  auto second = StartAgent("twin", tall_map_path_, {"--claim-wait", "5"});
  EXPECT_EQ(second->Wait(kDeadline), 2) << second->Output();
  EXPECT_NE(second->Output().find("robot id twin is already taken on DDS domain"),
            std::string::npos)
      << second->Output();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("twin             active"), std::string::npos) << server.Output();
}

TEST_F(FleetDdsTest, ASecondAgentThatSkipsTheCheckIsRefusedAndTheFirstIsWarned) {
  Subprocess server({kServer, "--duration", "60"}, env_);
  auto first = StartAgent("twin", map_path_);
  ASSERT_TRUE(server.WaitForOutput("robot twin joined", kDeadline)) << server.Output();
  auto second = StartAgent("twin", tall_map_path_, {"--claim-wait", "0"});
  EXPECT_TRUE(server.WaitForOutput("claims robot id twin, which participant", kDeadline))
      << server.Output();
  EXPECT_TRUE(first->WaitForOutput("also claims robot id twin", kDeadline)) << first->Output();
  // The second agent's departure must not end the first's robot.
  second->Signal(SIGINT);
  EXPECT_EQ(second->Wait(kDeadline), 0) << second->Output();
  std::this_thread::sleep_for(seconds(3));  // past the liveliness lease: a wrong "lost" shows
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("twin             active"), std::string::npos) << server.Output();
  EXPECT_EQ(server.Output().find("robot twin left"), std::string::npos) << server.Output();
}

TEST_F(FleetDdsTest, RestartedServerResumesTheFusedMapFromItsStore) {
  const std::string store = ::testing::TempDir() + "/fleet_store_" + std::to_string(getpid()) +
                            "_" + std::to_string(domain_) + ".db";
  std::remove(store.c_str());
  auto server = std::make_unique<Subprocess>(
      std::vector<std::string>{kServer, "--duration", "60", "--store", store}, env_);
  {
    auto agent = StartAgent("alpha", map_path_);
    ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
    ASSERT_TRUE(agent->WaitForOutput("changed tiles", kDeadline));
    // Let the server receive, fuse and store; then the agent goes, so nothing can resend.
    std::this_thread::sleep_for(std::chrono::seconds(2));
    agent->Signal(SIGTERM);
    ASSERT_EQ(agent->Wait(kDeadline), 0);
  }
  server->Signal(SIGKILL);
  server->Wait(kDeadline);

  Subprocess restarted({kServer, "--duration", "60", "--store", store}, env_);
  EXPECT_TRUE(restarted.WaitForOutput("restored", kDeadline)) << restarted.Output();
  ExpectFleetMapShowsMap(map_path_, restarted);
  restarted.Signal(SIGINT);
  EXPECT_EQ(restarted.Wait(kDeadline), 0);
  std::remove(store.c_str());
}

// A robot tile as fleetmap-vmap/3 (wire format version 3) laid it out: uint16 obstacle sizes and
// half widths in quanta. A store written by that version holds such payloads.
std::string VersionThreeTilePayload(const std::string& robot) {
  std::string bytes(512, '\0');
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  cdr << robot << int32_t{1} << int32_t{0} << int32_t{0} << uint32_t{0};  // key, stamp
  cdr << std::string("fleet") << uint32_t{1} << 10.0 << 10.0 / 16000 << 0.0707f << 0.05f;
  cdr << std::vector<uint16_t>{2} << std::vector<uint16_t>{80};  // sizes, half widths
  cdr << std::vector<int16_t>{0, 8000} << std::vector<int16_t>{4000, 4000};
  cdr << std::vector<int16_t>{} << std::vector<int16_t>{} << std::vector<uint16_t>{};
  cdr << std::vector<uint16_t>{} << std::vector<uint16_t>{} << std::vector<int16_t>{}
      << std::vector<int16_t>{};
  bytes.resize(cdr.getSerializedDataLength());
  return bytes;
}

// A tile of layout 4 (int16 arrays, layout_version 4 after frame_id), as a store written by the
// previous fleetmap holds it.
std::string VersionFourTilePayload(const std::string& robot) {
  std::string bytes(512, '\0');
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  cdr << robot << int32_t{2} << int32_t{0} << int32_t{0} << uint32_t{0};  // key, stamp
  cdr << std::string("fleet") << uint32_t{1} << uint8_t{4} << 10.0 << 10.0 / 16000 << 0.0707f
      << 0.05f;
  cdr << std::vector<uint8_t>{2} << std::vector<uint8_t>{};  // sizes, half widths
  cdr << std::vector<int16_t>{0, 8000} << std::vector<int16_t>{4000, 4000};
  cdr << std::vector<int16_t>{} << std::vector<int16_t>{} << std::vector<uint8_t>{};
  cdr << std::vector<uint16_t>{} << std::vector<uint16_t>{} << std::vector<int16_t>{}
      << std::vector<int16_t>{};
  bytes.resize(cdr.getSerializedDataLength());
  return bytes;
}

TEST_F(FleetDdsTest, StoredTilesOfAnOlderWireFormatAreSkippedAndTheRestRestored) {
  const std::string path = ::testing::TempDir() + "/fleet_old_store_" + std::to_string(getpid()) +
                           "_" + std::to_string(domain_) + ".db";
  std::remove(path.c_str());
  {
    auto store = store::MapStore::Open(path);
    ASSERT_TRUE(store.ok()) << store.status();
    transport::VectorTileMessage tile;
    tile.robot_id = RobotId{"alpha"};
    tile.tile = TileId{0, 0};
    tile.revision = 1;
    tile.map.frame_id = "fleet";
    tile.map.epsilon = 0.0707;
    tile.map.obstacles.push_back({{Point2(1.0, 5.0), Point2(9.0, 5.0)}, false, 0.0});
    const StatusOr<std::string> good = transport::EncodeTilePayload(tile);
    ASSERT_TRUE(good.ok()) << good.status();
    ASSERT_TRUE(
        (*store)
            ->PutTiles({{store::TileOwner::Robot(RobotId{"alpha"}), TileId{0, 0}, 1, 1, *good},
                        {store::TileOwner::Robot(RobotId{"beta"}), TileId{1, 0}, 1, 1,
                         VersionThreeTilePayload("beta")},
                        {store::TileOwner::Robot(RobotId{"gamma"}), TileId{2, 0}, 1, 1,
                         VersionFourTilePayload("gamma")}})
            .ok());
  }
  Subprocess server({kServer, "--duration", "30", "--store", path}, env_);
  EXPECT_TRUE(server.WaitForOutput("restored 1 robot tiles", kDeadline)) << server.Output();
  EXPECT_NE(server.Output().find("skipping a stored tile: " + path +
                                 ": tile_latest row of beta's tile (1, 0)"),
            std::string::npos)
      << server.Output();
  // Layout 4's frame_id length lands where layout 5 has layout_version: refused by name.
  EXPECT_NE(server.Output().find("gamma's tile (2, 0) revision 1: layout_version is 6 (layouts "
                                 "3 and 4 read so), this fleetmap reads 5"),
            std::string::npos)
      << server.Output();
  server.Signal(SIGINT);
  EXPECT_EQ(server.Wait(kDeadline), 0) << server.Output();
  std::remove(path.c_str());
}

TEST_F(FleetDdsTest, AgentRefusesBadMapWithExitCodeTwo) {
  const auto result =
      process::RunCommand({kAgent, "--robot-id", "alpha", "--map", "/nonexistent/map.yaml",
                           "--domain", std::to_string(domain_), "--localhost-only"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output().find("/nonexistent/map.yaml"), std::string::npos) << result.output();
}

TEST_F(FleetDdsTest, ABadDiscoveryServerListIsNamedWithExitCodeTwo) {
  for (const std::string& binary : {kAgent, kServer}) {
    std::vector<std::string> argv = {binary, "--discovery-server", "127.0.0.1:port"};
    if (binary == kAgent) argv.insert(argv.end(), {"--robot-id", "alpha", "--map", map_path_});
    const auto result = process::RunCommand(argv);
    EXPECT_EQ(result.exit_code, 2) << binary << ": " << result.output();
    EXPECT_NE(result.output().find("--discovery-server \"127.0.0.1:port\""), std::string::npos)
        << result.output();
  }
}

TEST_F(FleetDdsTest, AgentRefusesBadRobotName) {
  const auto result = process::RunCommand({kAgent, "--robot-id", "no/slash", "--map", map_path_});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output().find("no/slash"), std::string::npos) << result.output();
}

TEST_F(FleetDdsTest, AgentRefusesWireOptionsThatDoNotGoTogether) {
  // The grid wires are measured beside the tile wire only; an unknown wire is named. (A rotated
  // given frame works on every wire: GivenFrameTest.)
  const auto measured = process::RunCommand(
      {kAgent, "--robot-id", "alpha", "--map", map_path_, "--wire", "grid", "--measure-baselines"});
  EXPECT_EQ(measured.exit_code, 2);
  EXPECT_NE(measured.output().find("--measure-baselines"), std::string::npos) << measured.output();
  const auto unknown =
      process::RunCommand({kAgent, "--robot-id", "alpha", "--map", map_path_, "--wire", "png"});
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output().find("--wire"), std::string::npos) << unknown.output();
}

}  // namespace
}  // namespace fleetmap
