// A DDS participant of another vendor (Cyclone DDS, built from idl/ alone) and fleetmap (Fast DDS
// 2.9) understand each other on loopback: the hostile peer's samples reach fleetmap's readers and
// a real server, so the tests of issue 15 that use it exercise the server's logic, not a
// transport mismatch.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <limits>
#include <map>
#include <string>

#include "common/core/wake_up.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/hostile_peer.hpp"

namespace fleetmap {
namespace {

using std::chrono::seconds;
constexpr seconds kDeadline{20};

std::unique_ptr<transport::Participant> TestParticipant(int domain) {
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  auto participant = transport::Participant::Create(options);
  EXPECT_TRUE(participant.ok()) << participant.status();
  return participant.ok() ? std::move(participant).value() : nullptr;
}

// Drains `reader` until a tile event for `tile` of `robot` satisfies `accept`, or the deadline.
template <typename Accept>
bool WaitForTile(transport::VectorTileReader& reader, WakeUp& wake_up, const std::string& robot,
                 TileId tile, Accept accept) {
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < deadline) {
    wake_up.WaitFor(std::chrono::milliseconds(200));
    for (const transport::TileEvent& event : reader.Drain()) {
      if (event.kind == transport::TileEvent::Kind::kTile && event.tile.robot_id.value == robot &&
          event.tile.tile == tile && accept(event.tile)) {
        return true;
      }
    }
  }
  return false;
}

TEST(HostilePeerTest, FastDdsReaderDecodesTheCycloneTile) {
  const int domain = process::RandomDomainId();
  auto participant = TestParticipant(domain);
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader =
      transport::VectorTileReader::Create(*participant, transport::kRobotTilesTopic, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  auto peer = testing::HostilePeer::Start(
      domain, {"--robot-id", "intruder", "--tile", "3,-4", "--duration", "30"});
  // The wall tile: a closed square wall (4 corners) and one point obstacle, all in their tile.
  EXPECT_TRUE(WaitForTile(**reader, *wake_up, "intruder", TileId{3, -4},
                          [](const transport::VectorTileMessage& tile) {
                            const auto& obstacles = tile.map.obstacles;
                            return tile.tile_size == 10.0 && obstacles.size() == 2 &&
                                   obstacles[0].closed && obstacles[0].points.size() == 4 &&
                                   std::abs(obstacles[0].points[0].x() - 31.25) < 1e-9 &&
                                   std::abs(obstacles[0].points[0].y() + 38.75) < 1e-9 &&
                                   obstacles[1].points.size() == 1 &&
                                   tile.map.free_space.size() == 1;
                          }))
      << peer->Output();
  EXPECT_TRUE(peer->WaitForOutput("matched 1 reader(s) on rt/fleetmap/robot_tiles", kDeadline))
      << peer->Output();
  peer->Signal(SIGINT);
  EXPECT_EQ(peer->Wait(kDeadline), 0) << peer->Output();
}

// The scenarios' tiles are valid by the wire format, so they reach a receiver's logic instead of
// its shape checks: a far key, an empty robot id, a heavy flood tile, a hijacker's all-free tile.
TEST(HostilePeerTest, ScenarioTilesPassFleetmapsChecks) {
  const int domain = process::RandomDomainId();
  auto participant = TestParticipant(domain);
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto reader =
      transport::VectorTileReader::Create(*participant, transport::kRobotTilesTopic, wake_up);
  ASSERT_TRUE(reader.ok()) << reader.status();

  auto peer = testing::HostilePeer::Start(
      domain,
      {"--far-key", "--empty-id", "--flood", "--flood-tiles", "1", "--flood-vertices", "600",
       "--flood-rate", "2", "--flood-origin", "5,5", "--hijack", "ghost", "--duration", "30"});
  constexpr int32_t kMax = std::numeric_limits<int32_t>::max();
  bool far = false, empty = false, heavy = false, forged = false;
  int rejected = 0;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (!(far && empty && heavy && forged) && std::chrono::steady_clock::now() < deadline) {
    wake_up->WaitFor(std::chrono::milliseconds(200));
    for (const transport::TileEvent& event : (*reader)->Drain()) {
      if (event.kind == transport::TileEvent::Kind::kRejected) {
        ++rejected;
        ADD_FAILURE() << event.error;
        continue;
      }
      if (event.kind != transport::TileEvent::Kind::kTile) continue;
      const transport::VectorTileMessage& tile = event.tile;
      far |= tile.tile == TileId{kMax, kMax} && tile.robot_id.value == "intruder";
      empty |= tile.robot_id.value.empty() && !tile.map.obstacles.empty();
      // 600 vertices in polylines of at most 255.
      size_t vertices = 0;
      for (const auto& polyline : tile.map.obstacles) vertices += polyline.points.size();
      heavy |= tile.tile == TileId{5, 5} && tile.map.obstacles.size() == 3 && vertices == 600;
      forged |= tile.robot_id.value == "ghost" && tile.map.obstacles.empty() &&
                tile.map.free_space.size() == 1;
    }
  }
  EXPECT_TRUE(far) << peer->Output();
  EXPECT_TRUE(empty) << peer->Output();
  EXPECT_TRUE(heavy) << peer->Output();
  EXPECT_TRUE(forged) << peer->Output();
  EXPECT_EQ(rejected, 0);
  peer->Signal(SIGINT);
  EXPECT_EQ(peer->Wait(kDeadline), 0) << peer->Output();
}

TEST(HostilePeerTest, ServerJoinsAndFusesTheCycloneRobot) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server({testing::kServerBinary, "--duration", "60"}, env);
  ASSERT_TRUE(server.WaitForOutput("listening on DDS domain", kDeadline)) << server.Output();

  auto participant = TestParticipant(domain);
  ASSERT_NE(participant, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto fused =
      transport::VectorTileReader::Create(*participant, transport::kFusedTilesTopic, wake_up);
  ASSERT_TRUE(fused.ok()) << fused.status();

  auto peer = testing::HostilePeer::Start(
      domain, {"--robot-id", "intruder", "--tile", "0,0", "--duration", "30"});
  EXPECT_TRUE(server.WaitForOutput("robot intruder joined (tiles wire", kDeadline))
      << server.Output() << peer->Output();
  // The server fused the peer's walls: the fused tile (0, 0) has obstacles.
  EXPECT_TRUE(WaitForTile(
      **fused, *wake_up, "fleet", TileId{0, 0},
      [](const transport::VectorTileMessage& tile) { return !tile.map.obstacles.empty(); }))
      << server.Output() << peer->Output();

  peer->Signal(SIGINT);
  EXPECT_EQ(peer->Wait(kDeadline), 0) << peer->Output();
  fused->reset();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  // The summary counts the intruder's tile as taken.
  EXPECT_NE(server.Output().find("intruder"), std::string::npos) << server.Output();
}

}  // namespace
}  // namespace fleetmap
