// Contradiction quarantine between real processes (docs/fleet.md, "Quarantine"): a robot whose map
// calls free the walls another robot established (a fresh id painting free space, or an honest
// robot given a transform 2 m off) is quarantined within the fusion step that would have erased
// them; rt/fleetmap/map keeps every wall, rt/fleetmap/robot_frames says why, and `fleetmap admit`
// lets an operator overrule it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "common/core/wake_up.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/integration/loopback_participant.hpp"
#include "tests/integration/occupied_cells.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;
using Standing = transport::RobotFrameMessage::Standing;

// Bounds on waits for a loaded 2-core machine, not assertions about time.
constexpr seconds kDeadline{30};

// Rooms of walls (a 6 m grid of them) over 19 x 19 m, all seen; or the same extent all free.
std::string WriteMap(const std::string& name, bool walls) {
  grid::OccupancyGrid map(384, 384, 0.05, Pose2{0.5, 0.5, 0.0}, grid::kFreeValue);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (walls && (x % 120 == 10 || y % 120 == 10)) map.at(x, y) = grid::kOccupiedValue;
    }
  }
  const std::string path =
      ::testing::TempDir() + "/quarantine_" + std::to_string(getpid()) + "_" + name + ".yaml";
  EXPECT_TRUE(grid::SaveMap(map, path).ok());
  return path;
}

using testing::OccupiedCells;

class QuarantineTest : public ::testing::Test {
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
    auto frames = transport::RobotFrameReader::Create(*participant_, wake_up_);
    ASSERT_TRUE(frames.ok()) << frames.status();
    frames_ = std::move(frames).value();
  }

  void TearDown() override {
    maps_.reset();
    frames_.reset();
    participant_.reset();
  }

  std::unique_ptr<Subprocess> Start(std::vector<std::string> argv) {
    auto process = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(process->started());
    return process;
  }

  // Drains both readers for `for_how_long` (or until `done` says so); keeps the newest of each.
  void Follow(milliseconds for_how_long, const std::function<bool()>& done = nullptr) {
    const auto until = std::chrono::steady_clock::now() + for_how_long;
    while (std::chrono::steady_clock::now() < until) {
      wake_up_->WaitFor(milliseconds(100));
      for (StatusOr<transport::MapMessage>& map : maps_->Drain()) {
        if (map.ok()) map_ = std::move(map).value();
      }
      for (transport::RobotFrameEvent& event : frames_->Drain()) {
        if (event.kind == transport::RobotFrameEvent::Kind::kSample) {
          frames_seen_[event.message.robot.value] = event.message;
        }
      }
      if (done && done()) return;
    }
  }

  std::optional<Standing> StandingOf(const std::string& robot) const {
    const auto it = frames_seen_.find(robot);
    if (it == frames_seen_.end()) return std::nullopt;
    return it->second.standing;
  }

  int domain_ = 0;
  std::map<std::string, std::string> env_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::OccupancyGridReader> maps_;
  std::unique_ptr<transport::RobotFrameReader> frames_;
  std::optional<transport::MapMessage> map_;
  std::map<std::string, transport::RobotFrameMessage> frames_seen_;
};

TEST_F(QuarantineTest, AFreshIdPaintingFreeSpaceErasesNoWallAndAnOperatorCanAdmitIt) {
  const std::string walls = WriteMap("walls", true);
  const std::string free_space = WriteMap("free", false);
  auto server = Start({testing::kServerBinary, "--duration", "90"});
  auto alpha = Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", walls});
  std::set<std::pair<int, int>> established;
  Follow(kDeadline, [&] {
    if (!map_) return false;
    established = OccupiedCells(map_->grid);
    return established.size() > 3000;
  });
  ASSERT_GT(established.size(), 3000u) << server->Output();
  Follow(seconds(2));  // alpha's map settles
  established = OccupiedCells(map_->grid);

  auto mallory = Start({testing::kAgentBinary, "--robot-id", "mallory", "--map", free_space});
  ASSERT_TRUE(server->WaitForOutput("robot mallory quarantined", kDeadline)) << server->Output();
  // Quarantined on its first tiles; the figures follow as the rest of its map arrives.
  const auto quarantined_over_100_m = [&] {
    return StandingOf("mallory") == Standing::kQuarantined &&
           frames_seen_.at("mallory").contradicted_m > 100.0;
  };
  Follow(kDeadline, quarantined_over_100_m);
  ASSERT_EQ(StandingOf("mallory"), Standing::kQuarantined);
  const transport::RobotFrameMessage& frame = frames_seen_.at("mallory");
  EXPECT_GT(frame.contradicted_share, 0.9);
  EXPECT_GT(frame.contradicted_m, 100.0);
  EXPECT_LT(frame.area_min.x(), frame.area_max.x());
  EXPECT_NE(frame.standing_reason.find("walls other robots established"), std::string::npos);
  EXPECT_EQ(StandingOf("alpha").value_or(Standing::kQuarantined), Standing::kTrusted);

  Follow(seconds(3));  // every fused map the server publishes meanwhile
  ASSERT_TRUE(map_.has_value());
  const std::set<std::pair<int, int>> after = OccupiedCells(map_->grid);
  size_t erased = 0;
  for (const auto& cell : established) erased += after.count(cell) == 0;
  EXPECT_EQ(erased, 0u) << "of " << established.size() << " established wall cells";

  // The operator overrules the quarantine: mallory's newer free space is fused.
  const process::CommandResult admitted =
      testing::RunFleetmap({"admit", "mallory", "--domain", std::to_string(domain_),
                            "--localhost-only", "--operator", "test"},
                           seconds(60));
  EXPECT_EQ(admitted.exit_code, 0) << admitted.output();
  EXPECT_NE(admitted.out.find("admitted out of quarantine"), std::string::npos)
      << admitted.output();
  EXPECT_TRUE(server->WaitForOutput("robot mallory admitted by test", kDeadline))
      << server->Output();
  Follow(kDeadline,
         [&] { return map_ && OccupiedCells(map_->grid).size() < established.size() / 2; });
  EXPECT_LT(OccupiedCells(map_->grid).size(), established.size() / 2);
  server->Signal(SIGINT);
  EXPECT_EQ(server->Wait(kDeadline), 0);
  EXPECT_NE(server->StdOut().find("quarantine: 1 robots entered it"), std::string::npos)
      << server->StdOut();
}

TEST_F(QuarantineTest, AnAdmissionOutlivesARestartOfTheServer) {
  const std::string walls = WriteMap("walls", true);
  const std::string free_space = WriteMap("free", false);
  const std::string store =
      ::testing::TempDir() + "/quarantine_admitted_" + std::to_string(getpid()) + ".db";
  std::filesystem::remove(store);
  auto server = Start({testing::kServerBinary, "--duration", "90", "--store", store});
  auto alpha = Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", walls});
  Follow(kDeadline, [&] { return map_ && OccupiedCells(map_->grid).size() > 3000; });
  ASSERT_TRUE(map_.has_value()) << server->Output();
  Follow(seconds(2));
  const size_t established = OccupiedCells(map_->grid).size();
  auto mallory = Start({testing::kAgentBinary, "--robot-id", "mallory", "--map", free_space});
  ASSERT_TRUE(server->WaitForOutput("robot mallory quarantined", kDeadline)) << server->Output();
  const process::CommandResult admitted =
      testing::RunFleetmap({"admit", "mallory", "--domain", std::to_string(domain_),
                            "--localhost-only", "--operator", "test"},
                           seconds(60));
  ASSERT_EQ(admitted.exit_code, 0) << admitted.output();
  ASSERT_TRUE(server->WaitForOutput("robot mallory admitted by test", kDeadline))
      << server->Output();
  server->Signal(SIGINT);
  ASSERT_EQ(server->Wait(kDeadline), 0) << server->Output();

  // The restarted server weighs mallory's stored evidence again: admitted, it is fused at once.
  frames_seen_.clear();
  map_.reset();
  auto restarted = Start({testing::kServerBinary, "--duration", "60", "--store", store});
  ASSERT_TRUE(restarted->WaitForOutput("admitted by an operator before: mallory", kDeadline))
      << restarted->Output();
  Follow(kDeadline, [&] {
    return map_ && OccupiedCells(map_->grid).size() < established / 2 &&
           StandingOf("mallory") == Standing::kAdmitted;
  });
  ASSERT_TRUE(map_.has_value()) << restarted->Output();
  EXPECT_LT(OccupiedCells(map_->grid).size(), established / 2);
  EXPECT_EQ(StandingOf("mallory"), Standing::kAdmitted);
  EXPECT_EQ(restarted->Output().find("robot mallory quarantined"), std::string::npos)
      << restarted->Output();
}

TEST_F(QuarantineTest, AnHonestRobotGivenATransformTwoMetresOffIsQuarantined) {
  const std::string walls = WriteMap("walls", true);
  auto server = Start({testing::kServerBinary, "--duration", "90"});
  auto alpha = Start({testing::kAgentBinary, "--robot-id", "alpha", "--map", walls});
  Follow(kDeadline, [&] { return map_ && OccupiedCells(map_->grid).size() > 3000; });
  Follow(seconds(2));
  ASSERT_TRUE(map_.has_value());
  const std::set<std::pair<int, int>> established = OccupiedCells(map_->grid);
  // The same building, mapped again by a robot whose frame is given 2 m off.
  auto beta = Start({testing::kAgentBinary, "--robot-id", "beta", "--map", walls,
                     "--fleet-from-map", "2", "0", "0"});
  ASSERT_TRUE(server->WaitForOutput("robot beta quarantined", kDeadline)) << server->Output();
  Follow(seconds(3));
  const std::set<std::pair<int, int>> after = OccupiedCells(map_->grid);
  size_t erased = 0;
  for (const auto& cell : established) erased += after.count(cell) == 0;
  EXPECT_EQ(erased, 0u);
  EXPECT_EQ(StandingOf("beta"), Standing::kQuarantined);
}

TEST_F(QuarantineTest, AdmitRefusesABadNameAndSaysWhenNoServerAnswers) {
  const process::CommandResult bad = testing::RunFleetmap(
      {"admit", "not a name", "--domain", std::to_string(domain_), "--localhost-only"});
  EXPECT_EQ(bad.exit_code, 2) << bad.output();
  EXPECT_NE(bad.err.find("is not a robot name"), std::string::npos) << bad.err;
  const process::CommandResult nobody =
      testing::RunFleetmap({"admit", "mallory", "--domain", std::to_string(domain_),
                            "--localhost-only", "--timeout", "2"});
  EXPECT_EQ(nobody.exit_code, 1) << nobody.output();
  EXPECT_NE(nobody.err.find("no fleetmap-server reads rt/fleetmap/admissions"), std::string::npos)
      << nobody.err;
}

}  // namespace
}  // namespace fleetmap
