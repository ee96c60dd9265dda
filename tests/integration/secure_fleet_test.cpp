// Issue 19, live: a fleet secured with credentials made by `fleetmap security` in a temporary
// folder. Real fleetmap-server and fleetmap-agent processes, real DDS Security (PKI-DH,
// AES-GCM, signed governance and permissions) over loopback, a random domain per test. An
// unenrolled participant (Fast DDS, or Cyclone DDS: another vendor) reads and writes nothing; an
// enrolled robot cannot write as another robot (the server checks the writer's identity) nor as
// the server (its permissions); a revoked robot is refused by a server that has the new list;
// expired and foreign credentials stop a process at start, naming the file; SIGTERM and SIGINT
// end secured processes cleanly.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "common/core/wake_up.hpp"
#include "common/process/subprocess.hpp"
#include "common/security/fleet_security.hpp"
#include "common/security/security_folder.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/transport/vector_tile_writer.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/integration/hostile_peer.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap {
namespace {

namespace fs = std::filesystem;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;
using ::testing::HasSubstr;
using ::testing::Not;

// Bounds waits on a loaded 2-core CI machine (handshakes included); not an assertion about speed.
constexpr seconds kDeadline{60};

const std::string kMap = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";

class SecureFleetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"security", "init", "--dir", dir_},
          {"security", "enroll", "--dir", dir_, "--robot", "alpha"},
          {"security", "enroll", "--dir", dir_, "--robot", "bravo"},
          {"security", "enroll", "--dir", dir_, "--viewer", "watch"}}) {
      const process::CommandResult made = testing::RunFleetmap(args);
      ASSERT_EQ(made.exit_code, 0) << made.output();
    }
    domain_ = process::RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  }

  std::unique_ptr<Subprocess> Start(std::vector<std::string> argv) {
    auto process = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(process->started());
    return process;
  }
  std::unique_ptr<Subprocess> StartServer(const std::string& dir) {
    return Start({testing::kServerBinary, "--duration", "120", "--no-object-learning",
                  "--no-extrapolation", "--security", dir});
  }
  std::unique_ptr<Subprocess> StartAgent(const std::string& robot, const std::string& dir) {
    return Start({testing::kAgentBinary, "--robot-id", robot, "--map", kMap, "--security", dir});
  }

  // An in-process participant on the test's domain: secured as `identity`, or not at all.
  std::unique_ptr<transport::Participant> Participant(const std::string& identity) {
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    if (!identity.empty()) {
      const Status secured = options.UseSecurityFolder(dir_, identity);
      EXPECT_TRUE(secured.ok()) << secured;
    }
    auto participant = transport::Participant::Create(options);
    EXPECT_TRUE(participant.ok()) << participant.status();
    return participant.ok() ? std::move(participant).value() : nullptr;
  }

  testing::ScratchDir scratch_{"security"};
  std::string dir_ = scratch_.Path("fleet");
  int domain_ = 0;
  std::map<std::string, std::string> env_;
};

// Fused tiles received by `reader` until `deadline` or until `enough`.
size_t CountTiles(transport::VectorTileReader& reader, WakeUp& wake_up,
                  std::chrono::steady_clock::time_point deadline, size_t enough) {
  size_t tiles = 0;
  while (std::chrono::steady_clock::now() < deadline && tiles < enough) {
    wake_up.WaitFor(milliseconds(100));
    for (const transport::TileEvent& event : reader.Drain()) {
      if (event.kind == transport::TileEvent::Kind::kTile) ++tiles;
    }
  }
  return tiles;
}

TEST_F(SecureFleetTest, AnEnrolledFleetFusesWhileAnUnenrolledParticipantSeesAndSendsNothing) {
  auto server = StartServer(dir_);
  auto alpha = StartAgent("alpha", dir_);
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();

  auto viewer = Participant("watch");
  auto outsider = Participant("");
  ASSERT_NE(viewer, nullptr);
  ASSERT_NE(outsider, nullptr);
  auto wake_up = std::make_shared<WakeUp>();
  auto viewer_tiles =
      transport::VectorTileReader::Create(*viewer, transport::kFusedTilesTopic, wake_up);
  auto outsider_tiles =
      transport::VectorTileReader::Create(*outsider, transport::kFusedTilesTopic, wake_up);
  auto outsider_statuses = transport::RobotStatusReader::Create(*outsider, wake_up);
  auto outsider_writer = transport::RobotStatusWriter::Create(*outsider);
  ASSERT_TRUE(viewer_tiles.ok()) << viewer_tiles.status();
  ASSERT_TRUE(outsider_tiles.ok()) << outsider_tiles.status();
  ASSERT_TRUE(outsider_statuses.ok()) << outsider_statuses.status();
  ASSERT_TRUE(outsider_writer.ok()) << outsider_writer.status();

  // The enrolled viewer gets the fused map (transient local: all of it) ...
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  EXPECT_GT(CountTiles(**viewer_tiles, *wake_up, deadline, 1), 0u) << server->Output();
  // ... while the outsider, on the same domain for as long, hears nothing and is not heard.
  RobotStatus intruder;
  intruder.robot = RobotId{"intruder"};
  for (int i = 0; i < 30; ++i) {
    intruder.stamp = Clock::now();
    EXPECT_TRUE((*outsider_writer)->Write(intruder).ok());
    wake_up->WaitFor(milliseconds(100));
  }
  EXPECT_TRUE((*outsider_tiles)->Drain().empty());
  // Its own statuses come back to it (same participant); alpha's never do.
  for (const transport::RobotEvent& event : (*outsider_statuses)->Drain()) {
    EXPECT_EQ(event.robot.value, "intruder");
  }
  EXPECT_THAT(server->Output(), Not(HasSubstr("intruder")));

  outsider_writer->reset();
  outsider_statuses->reset();
  outsider_tiles->reset();
  viewer_tiles->reset();
}

TEST_F(SecureFleetTest, AnEnrolledRobotCannotWriteAsAnotherRobotNorAsTheServer) {
  auto server = StartServer(dir_);
  ASSERT_TRUE(server->WaitForOutput("listening", kDeadline)) << server->Output();
  auto alpha = Participant("alpha");
  ASSERT_NE(alpha, nullptr);

  // Its permissions allow no writer on the server's topics nor on another robot's grid: DDS
  // refuses to make one. Its own grid topic is allowed (the control).
  EXPECT_FALSE(transport::VectorTileWriter::Create(*alpha, transport::kFusedTilesTopic).ok());
  EXPECT_FALSE(transport::OccupancyGridWriter::Create(*alpha, transport::kFleetMapTopic).ok());
  EXPECT_FALSE(
      transport::OccupancyGridWriter::Create(*alpha, transport::RobotMapTopic(RobotId{"bravo"}))
          .ok());
  auto own_grid =
      transport::OccupancyGridWriter::Create(*alpha, transport::RobotMapTopic(RobotId{"alpha"}));
  EXPECT_TRUE(own_grid.ok()) << own_grid.status();

  // Its permissions do allow statuses (in its own partition), so a status naming bravo reaches
  // the server, which checks the writer's identity and refuses it.
  auto writer = transport::RobotStatusWriter::Create(*alpha);
  ASSERT_TRUE(writer.ok()) << writer.status();
  RobotStatus forged;
  forged.robot = RobotId{"bravo"};
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  bool refused = false;
  while (!refused && std::chrono::steady_clock::now() < deadline) {
    forged.stamp = Clock::now();
    EXPECT_TRUE((*writer)->Write(forged).ok());
    refused = server->WaitForOutput("claims robot id bravo", milliseconds(200));
  }
  EXPECT_TRUE(refused) << server->Output();
  EXPECT_THAT(server->Output(), HasSubstr("authenticated as \"alpha\""));
  EXPECT_THAT(server->Output(), Not(HasSubstr("robot bravo joined")));
  writer->reset();
  if (own_grid.ok()) own_grid->reset();
  server->Signal(SIGINT);
  ASSERT_EQ(server->Wait(seconds(20)), 0) << server->Output();
  EXPECT_THAT(server->Output(), HasSubstr("not its identity"));
}

TEST_F(SecureFleetTest, ARevokedRobotIsRefusedByAServerWithTheNewList) {
  // bravo's machine keeps its copy of the folder from before the revocation.
  const std::string bravo_copy = scratch_.Path("bravo_machine");
  fs::copy(dir_, bravo_copy, fs::copy_options::recursive);
  const process::CommandResult revoked =
      testing::RunFleetmap({"security", "revoke", "--dir", dir_, "--robot", "bravo"});
  ASSERT_EQ(revoked.exit_code, 0) << revoked.output();
  const process::CommandResult shown = testing::RunFleetmap({"security", "show", "--dir", dir_});
  EXPECT_THAT(shown.out, HasSubstr("revoked"));

  // With the new list, bravo's own start stops at once, naming the certificate.
  const process::CommandResult refused_locally = process::RunCommand(
      {testing::kAgentBinary, "--robot-id", "bravo", "--map", kMap, "--security", dir_},
      seconds(30));
  EXPECT_EQ(refused_locally.exit_code, 2) << refused_locally.output();
  EXPECT_THAT(refused_locally.output(), HasSubstr("revoked"));

  // With its stale copy it starts, but the server's handshake refuses its certificate.
  auto server = StartServer(dir_);
  auto alpha = StartAgent("alpha", dir_);
  auto bravo = StartAgent("bravo", bravo_copy);
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  EXPECT_FALSE(server->WaitForOutput("robot bravo joined", seconds(10))) << server->Output();
  EXPECT_FALSE(bravo->Wait(milliseconds(0)).has_value()) << "bravo runs, unheard";
}

TEST_F(SecureFleetTest, ExpiredAndForeignCredentialsStopAtStartNamingTheFile) {
  const std::time_t now = std::time(nullptr);
  ASSERT_TRUE(security::Enroll(dir_, "old", security::Role::kRobot,
                               security::Validity{now - 10 * 86400, now - 86400})
                  .ok());
  const process::CommandResult expired = process::RunCommand(
      {testing::kAgentBinary, "--robot-id", "old", "--map", kMap, "--security", dir_}, seconds(30));
  EXPECT_EQ(expired.exit_code, 2) << expired.output();
  EXPECT_THAT(expired.output(), HasSubstr("identities/old/cert.pem"));
  EXPECT_THAT(expired.output(), HasSubstr("expired"));

  // The server's identity from another fleet's CA.
  const std::string other = scratch_.Path("other");
  ASSERT_TRUE(security::InitFleet(other, security::FleetSecurityOptions{}).ok());
  const std::string mixed = scratch_.Path("mixed");
  fs::copy(dir_, mixed, fs::copy_options::recursive);
  fs::remove_all(security::SecurityFolder(mixed).identity("server"));
  fs::copy(security::SecurityFolder(other).identity("server"),
           security::SecurityFolder(mixed).identity("server"), fs::copy_options::recursive);
  const process::CommandResult foreign = process::RunCommand(
      {testing::kServerBinary, "--duration", "5", "--security", mixed}, seconds(30));
  EXPECT_EQ(foreign.exit_code, 2) << foreign.output();
  EXPECT_THAT(foreign.output(), HasSubstr("identities/server/cert.pem"));
  EXPECT_THAT(foreign.output(), HasSubstr("not issued by the fleet CA"));

  const process::CommandResult missing = process::RunCommand(
      {testing::kServerBinary, "--duration", "5", "--security", scratch_.Path("nowhere")},
      seconds(30));
  EXPECT_EQ(missing.exit_code, 2) << missing.output();
  EXPECT_THAT(missing.output(), HasSubstr("nowhere"));
}

TEST_F(SecureFleetTest, SecuredProcessesEndCleanlyOnSigtermAndSigint) {
  auto server = StartServer(dir_);
  auto alpha = StartAgent("alpha", dir_);
  auto bravo = StartAgent("bravo", dir_);
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  ASSERT_TRUE(server->WaitForOutput("robot bravo joined", kDeadline)) << server->Output();
  alpha->Signal(SIGTERM);
  bravo->Signal(SIGINT);
  EXPECT_EQ(alpha->Wait(seconds(20)), 0) << alpha->Output();
  EXPECT_EQ(bravo->Wait(seconds(20)), 0) << bravo->Output();
  server->Signal(SIGTERM);
  EXPECT_EQ(server->Wait(seconds(20)), 0) << server->Output();

  // And a server that has authenticated no one yet, interrupted.
  auto lonely = StartServer(dir_);
  ASSERT_TRUE(lonely->WaitForOutput("listening", kDeadline)) << lonely->Output();
  lonely->Signal(SIGINT);
  EXPECT_EQ(lonely->Wait(seconds(20)), 0) << lonely->Output();
}

TEST_F(SecureFleetTest, AnotherVendorsPeerWithoutCredentialsCanNeitherReadNorHijack) {
  auto server = StartServer(dir_);
  auto alpha = StartAgent("alpha", dir_);
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  // Cyclone DDS, no credentials: it claims alpha's id, disposes it, and would erase alpha's
  // walls at the tile keys it reads on robot_tiles.
  auto peer = testing::HostilePeer::Start(
      domain_, {"--robot-id", "intruder", "--tile", "0,0", "--hijack", "alpha", "--duration", "8"});
  ASSERT_TRUE(peer->started());
  ASSERT_EQ(peer->Wait(seconds(60)), 0) << peer->Output();
  // It tried (it writes blindly) but read none of alpha's tiles ...
  ASSERT_THAT(peer->Output(), HasSubstr("hijack: disposed the robot_status instance of alpha"));
  EXPECT_THAT(peer->Output(), Not(HasSubstr("hijack: read the tiles of alpha")));
  server->Signal(SIGINT);
  ASSERT_EQ(server->Wait(seconds(20)), 0) << server->Output();
  // ... and the server heard none of it: no intruder, no disposal, nothing to refuse.
  EXPECT_THAT(server->Output(), Not(HasSubstr("intruder")));
  EXPECT_THAT(server->Output(), Not(HasSubstr("robot alpha left")));
  EXPECT_THAT(server->Output(), Not(HasSubstr("refused:")));
}

}  // namespace
}  // namespace fleetmap
