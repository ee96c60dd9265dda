// Issue 18, live: agents started with --unplaced do not know where their map frames sit in the
// fleet. A real fleetmap-server anchors the fleet on the first, registers the second robot's map
// (turned by 90 degrees and offset by tens of metres in its own frame) onto the fused map, fuses
// it, publishes the placement on rt/fleetmap/robot_frames and rt/tf, and revises it when the
// robot's map moves in its frame (as after a SLAM relocalisation). Real processes, DDS over
// loopback, a random domain per test.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/tf_topic.hpp"
#include "common/transport/topics.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/map_agreement.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;
using transport::RobotFrameMessage;

// Bounds waits on a loaded 2-core CI machine; not an assertion about speed.
constexpr seconds kDeadline{40};

// The cells [x0, x0 + w) of every row of `g`, as a map with its corner at `origin`.
grid::OccupancyGrid Columns(const grid::OccupancyGrid& g, int x0, int w, const Pose2& origin) {
  grid::OccupancyGrid out(w, g.height(), g.resolution(), origin);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < w; ++x) out.at(x, y) = g.at(x0 + x, y);
  }
  return out;
}

// `g`'s cells turned a quarter turn counter-clockwise, in a map whose origin is `origin`.
grid::OccupancyGrid QuarterTurn(const grid::OccupancyGrid& g, const Pose2& origin) {
  grid::OccupancyGrid out(g.height(), g.width(), g.resolution(), origin);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) out.at(g.height() - 1 - y, x) = g.at(x, y);
  }
  return out;
}

// Where QuarterTurn(g, origin)'s frame sits in g's frame (g's origin yaw 0).
Transform2 QuarterTurnFrame(const grid::OccupancyGrid& g, const Pose2& origin) {
  // Turned cell (x', y') = (H - 1 - y, x): the cell corner p' (metres from the turned grid's
  // corner) comes from p = (p'_y, H r - p'_x) metres from g's corner.
  Transform2 corner_from_turned = Transform2::Identity();
  corner_from_turned.translate(Point2(0.0, g.height() * g.resolution()));
  corner_from_turned.rotate(-M_PI / 2);
  return g.origin().ToTransform() * corner_from_turned * origin.ToTransform().inverse();
}

std::string Save(const grid::OccupancyGrid& map, const std::string& name) {
  const std::string path =
      ::testing::TempDir() + "/placement_" + std::to_string(getpid()) + "_" + name + ".yaml";
  const Status saved = grid::SaveMap(map, path);
  EXPECT_TRUE(saved.ok()) << saved;
  return path;
}

// How far `placed` puts the centre of `map` from where `truth` does (metres), and the yaw error.
std::pair<double, double> PlacementError(const Pose2& placed, const Transform2& truth,
                                         const grid::OccupancyGrid& map) {
  const Point2 centre = map.CellCenter(map.width() / 2, map.height() / 2);
  const double distance = (placed.ToTransform() * centre - truth * centre).norm();
  const double yaw =
      std::abs(NormalizeAngle(placed.yaw - std::atan2(truth.linear()(1, 0), truth.linear()(0, 0))));
  return {distance, yaw};
}

// Expects `placed` within `cells` cells of `truth` at the centre of `map`, and within a degree.
void ExpectPlacedAt(const Pose2& placed, const Transform2& truth, const grid::OccupancyGrid& map,
                    double cells, const Subprocess& server) {
  const auto [distance, yaw] = PlacementError(placed, truth, map);
  EXPECT_LE(distance, cells * map.resolution()) << server.Output();
  EXPECT_LE(yaw, 1.0 * M_PI / 180.0) << server.Output();
}

class PlacementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto house =
        grid::LoadMap(std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml");
    ASSERT_TRUE(house.ok()) << house.status();
    // alpha maps the right 60 % of the house, beta the left 60 %: they share a fifth of it.
    // alpha's frame: the house's, moved; beta's: turned a quarter and far away.
    const grid::OccupancyGrid& g = house->grid;
    const int w = g.width() * 3 / 5;
    const Pose2 alpha_origin{40.0, 7.5, 0.0};
    alpha_ = Columns(g, g.width() - w, w, alpha_origin);
    const grid::OccupancyGrid left = Columns(g, 0, w, g.origin());
    beta_ = QuarterTurn(left, Pose2{100.0, -50.0, 0.0});
    // Truth: the fleet frame is alpha's (it anchors). house <- alpha is a translation.
    const Transform2 house_from_alpha =
        Pose2{g.origin().x + (g.width() - w) * g.resolution() - alpha_origin.x,
              g.origin().y - alpha_origin.y, 0.0}
            .ToTransform();
    alpha_from_beta_ = house_from_alpha.inverse() * QuarterTurnFrame(left, beta_.origin());
    alpha_path_ = Save(alpha_, "alpha");
    beta_path_ = Save(beta_, "beta");

    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    auto participant = transport::Participant::Create(options);
    ASSERT_TRUE(participant.ok()) << participant.status();
    participant_ = std::move(participant).value();
    auto frames = transport::RobotFrameReader::Create(*participant_, wake_up_);
    ASSERT_TRUE(frames.ok()) << frames.status();
    frames_ = std::move(frames).value();
  }

  std::unique_ptr<Subprocess> Start(std::vector<std::string> argv) {
    auto process = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(process->started());
    return process;
  }
  std::unique_ptr<Subprocess> StartServer(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {testing::kServerBinary, "--duration", "90",
                                     "--no-object-learning", "--no-extrapolation"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return Start(std::move(argv));
  }
  std::unique_ptr<Subprocess> StartAgent(const std::string& robot, const std::string& map) {
    return Start({testing::kAgentBinary, "--robot-id", robot, "--map", map, "--unplaced"});
  }

  std::optional<RobotFrameMessage> WaitUntilPlaced(const std::string& robot) {
    return WaitForFrame(robot, [](const RobotFrameMessage& frame) { return frame.placed(); });
  }

  // Waits for a frame of `robot` that satisfies `done`; returns the last frame of `robot` seen.
  std::optional<RobotFrameMessage> WaitForFrame(
      const std::string& robot, const std::function<bool(const RobotFrameMessage&)>& done) {
    std::optional<RobotFrameMessage> last;
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up_->WaitFor(milliseconds(100));
      for (transport::RobotFrameEvent& event : frames_->Drain()) {
        EXPECT_NE(event.kind, transport::RobotFrameEvent::Kind::kRejected) << event.error;
        if (event.kind != transport::RobotFrameEvent::Kind::kSample) continue;
        if (event.message.robot.value != robot) continue;
        last = event.message;
        if (done(*last)) return last;
      }
    }
    return last;
  }

  grid::OccupancyGrid alpha_, beta_;
  Transform2 alpha_from_beta_;
  std::string alpha_path_, beta_path_;
  int domain_ = 0;
  std::map<std::string, std::string> env_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::RobotFrameReader> frames_;
};

TEST_F(PlacementTest, UnplacedRobotIsPlacedFusedAndPublishedOnRobotFramesAndTf) {
  auto server = StartServer();
  auto alpha = StartAgent("alpha", alpha_path_);
  const auto anchor = WaitForFrame("alpha", [](const RobotFrameMessage& frame) {
    return frame.state == RobotFrameMessage::State::kAnchor;
  });
  ASSERT_TRUE(anchor && anchor->state == RobotFrameMessage::State::kAnchor) << server->Output();
  EXPECT_EQ(anchor->fleet_from_map, Pose2{});

  auto tf = transport::TfReader::Create(*participant_);
  ASSERT_TRUE(tf.ok()) << tf.status();
  auto beta = StartAgent("beta", beta_path_);
  const auto placed = WaitForFrame("beta", [](const RobotFrameMessage& frame) {
    return frame.state == RobotFrameMessage::State::kPlaced;
  });
  ASSERT_TRUE(placed && placed->state == RobotFrameMessage::State::kPlaced) << server->Output();
  ExpectPlacedAt(placed->fleet_from_map, alpha_from_beta_, beta_, 2, *server);
  EXPECT_GE(placed->confidence, 0.5);
  EXPECT_GT(placed->overlap, 0.1);
  EXPECT_EQ(placed->placed_against, "fleet");
  EXPECT_EQ(placed->placements, 1u);

  // The agent learns where it is.
  EXPECT_TRUE(beta->WaitForOutput("placed by the server", kDeadline)) << beta->Output();

  // RViz's view: fleet -> beta/map on rt/tf, the same transform.
  std::optional<transport::FrameTransform> beta_tf;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (!beta_tf && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(100));
    for (const transport::FrameTransform& transform : (*tf)->Drain()) {
      if (transform.child == "beta/map") beta_tf = transform;
    }
  }
  ASSERT_TRUE(beta_tf.has_value()) << server->Output();
  EXPECT_EQ(beta_tf->parent, "fleet");
  EXPECT_NEAR(beta_tf->parent_from_child.x, placed->fleet_from_map.x, 1e-6);
  EXPECT_NEAR(beta_tf->parent_from_child.y, placed->fleet_from_map.y, 1e-6);
  EXPECT_NEAR(NormalizeAngle(beta_tf->parent_from_child.yaw - placed->fleet_from_map.yaw), 0.0,
              1e-6);

  // The fused map holds both robots' maps where they belong, once each: a wall counted twice or
  // a map in the wrong place would disagree with one of them.
  auto map_reader = transport::OccupancyGridReader::Create(*participant_, transport::kFleetMapTopic,
                                                           std::make_shared<WakeUp>());
  ASSERT_TRUE(map_reader.ok()) << map_reader.status();
  double alpha_agrees = 0.0, beta_agrees = 0.0;
  const auto map_deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < map_deadline &&
         (alpha_agrees < 0.95 || beta_agrees < 0.9)) {
    std::this_thread::sleep_for(milliseconds(200));
    for (auto& map : (*map_reader)->Drain()) {
      if (!map.ok()) continue;
      alpha_agrees = testing::Agreement(alpha_, Transform2::Identity(), map->grid);
      beta_agrees = testing::Agreement(beta_, alpha_from_beta_, map->grid);
    }
  }
  EXPECT_GE(alpha_agrees, 0.95) << server->Output();
  EXPECT_GE(beta_agrees, 0.9) << server->Output();
}

TEST_F(PlacementTest, PlacementThatTheMapContradictsIsRevised) {
  auto server = StartServer({"--placement-check-period", "1"});
  auto alpha = StartAgent("alpha", alpha_path_);
  ASSERT_TRUE(WaitUntilPlaced("alpha")) << server->Output();
  auto beta = StartAgent("beta", beta_path_);
  const auto placed = WaitUntilPlaced("beta");
  ASSERT_TRUE(placed && placed->placed()) << server->Output();

  // beta's SLAM moves its whole map 1.5 m along its x axis (a relocalisation): the old placement
  // now puts every wall of beta's map 1.5 m from where the fleet saw it.
  const Pose2 shift{1.5, 0.0, 0.0};
  grid::OccupancyGrid moved(beta_.width(), beta_.height(), beta_.resolution(),
                            Pose2{beta_.origin().x + shift.x, beta_.origin().y, 0.0});
  moved.mutable_data() = beta_.data();
  ASSERT_TRUE(grid::SaveMap(moved, beta_path_).ok());
  const Transform2 truth = alpha_from_beta_ * shift.ToTransform().inverse();

  const auto revised = WaitForFrame("beta", [](const RobotFrameMessage& frame) {
    return frame.state == RobotFrameMessage::State::kRevised;
  });
  ASSERT_TRUE(revised && revised->state == RobotFrameMessage::State::kRevised) << server->Output();
  ExpectPlacedAt(revised->fleet_from_map, truth, moved, 2, *server);
  EXPECT_EQ(revised->placements, 2u);
  EXPECT_TRUE(beta->WaitForOutput("revised by the server", kDeadline)) << beta->Output();
}

TEST_F(PlacementTest, ARobotOnAGridWireIsPlacedToo) {
  auto server = StartServer();
  auto alpha = StartAgent("alpha", alpha_path_);
  ASSERT_TRUE(WaitUntilPlaced("alpha")) << server->Output();
  auto beta = Start({testing::kAgentBinary, "--robot-id", "beta", "--map", beta_path_, "--unplaced",
                     "--wire", "grid-updates-zstd"});
  const auto placed = WaitUntilPlaced("beta");
  ASSERT_TRUE(placed && placed->placed()) << server->Output();
  ExpectPlacedAt(placed->fleet_from_map, alpha_from_beta_, beta_, 2, *server);
}

TEST_F(PlacementTest, ARobotMappingAtAnotherResolutionIsPlacedOnTheFleetMap) {
  // beta's SLAM runs at 2.5 cm: its map is rasterized at the fleet's 5 cm for registration.
  grid::OccupancyGrid fine(beta_.width() * 2, beta_.height() * 2, beta_.resolution() / 2,
                           beta_.origin());
  for (int y = 0; y < fine.height(); ++y) {
    for (int x = 0; x < fine.width(); ++x) fine.at(x, y) = beta_.at(x / 2, y / 2);
  }
  const std::string fine_path = Save(fine, "beta_fine");
  auto server = StartServer();
  auto alpha = StartAgent("alpha", alpha_path_);
  ASSERT_TRUE(WaitUntilPlaced("alpha")) << server->Output();
  auto beta = StartAgent("beta", fine_path);
  const auto placed = WaitUntilPlaced("beta");
  ASSERT_TRUE(placed && placed->placed()) << server->Output();
  ExpectPlacedAt(placed->fleet_from_map, alpha_from_beta_, beta_, 2, *server);
}

// Disabled: fails since group registration and the sequential test landed (gamma is not linked to
// beta within the deadline); to be fixed before issue 31 closes (see the stop note).
TEST_F(PlacementTest, RobotsRegisteredToEachOtherArePlacedTogether) {
  // gamma shares nothing with alpha (the anchor) but half its map with beta, and beta shares
  // nothing with alpha until its map grows: gamma is registered to beta first, and placed with
  // beta when beta reaches alpha's part of the house.
  const auto house =
      grid::LoadMap(std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml");
  ASSERT_TRUE(house.ok()) << house.status();
  const grid::OccupancyGrid& g = house->grid;
  const int w = g.width();
  const grid::OccupancyGrid east = Columns(g, w * 7 / 10, w - w * 7 / 10, Pose2{0.0, 0.0, 0.0});
  const grid::OccupancyGrid middle = Columns(g, w * 2 / 10, w * 4 / 10, Pose2{-30.0, 5.0, 0.0});
  const grid::OccupancyGrid grown = Columns(g, w * 2 / 10, w * 6 / 10, Pose2{-30.0, 5.0, 0.0});
  const grid::OccupancyGrid west_columns = Columns(g, 0, w * 4 / 10, g.origin());
  const grid::OccupancyGrid west = QuarterTurn(west_columns, Pose2{60.0, 60.0, 0.0});
  // house <- east: east's cell 0 is house column 0.7 w, and east's origin is (0, 0).
  const double r = g.resolution();
  const Transform2 house_from_east =
      Pose2{g.origin().x + (w * 7 / 10) * r, g.origin().y, 0.0}.ToTransform();
  const Transform2 truth =
      house_from_east.inverse() * QuarterTurnFrame(west_columns, west.origin());
  const std::string east_path = Save(east, "east");
  const std::string middle_path = Save(middle, "middle");
  const std::string west_path = Save(west, "west");

  auto server = StartServer();
  auto alpha = StartAgent("alpha", east_path);
  ASSERT_TRUE(WaitUntilPlaced("alpha")) << server->Output();
  auto beta = StartAgent("beta", middle_path);
  auto gamma = StartAgent("gamma", west_path);
  // Either registration links them (the sequential test confirms whichever comes first).
  const auto linked = [&] {
    const std::string out = server->Output();
    return out.find("robot gamma registered to robot beta") != std::string::npos ||
           out.find("robot beta registered to robot gamma") != std::string::npos;
  };
  const auto link_deadline = std::chrono::steady_clock::now() + kDeadline;
  while (!linked() && std::chrono::steady_clock::now() < link_deadline) {
    std::this_thread::sleep_for(milliseconds(200));
  }
  ASSERT_TRUE(linked()) << server->Output();
  ASSERT_TRUE(grid::SaveMap(grown, middle_path).ok());  // beta explores east
  const auto placed =
      WaitForFrame("gamma", [](const RobotFrameMessage& frame) { return frame.placed(); });
  ASSERT_TRUE(placed && placed->placed()) << server->Output();
  EXPECT_EQ(placed->placed_against, "beta");
  ExpectPlacedAt(placed->fleet_from_map, truth, west, 3, *server);
}

TEST_F(PlacementTest, AServerKilledMidRunPlacesAGoneRobotAgainFromItsStore) {
  const std::string store =
      ::testing::TempDir() + "/placement_" + std::to_string(getpid()) + "_store.sqlite";
  std::remove(store.c_str());
  const std::vector<std::string> server_argv = {
      testing::kServerBinary, "--store",    store, "--no-object-learning",
      "--no-extrapolation",   "--duration", "90"};
  auto server = Start(server_argv);
  auto alpha = StartAgent("alpha", alpha_path_);
  ASSERT_TRUE(WaitUntilPlaced("alpha")) << server->Output();
  auto beta = StartAgent("beta", beta_path_);
  ASSERT_TRUE(WaitUntilPlaced("beta")) << server->Output();
  // beta leaves; then the server dies without a word. Its store keeps beta's own-frame tiles.
  beta->Signal(SIGINT);
  ASSERT_TRUE(beta->Wait(kDeadline).has_value());
  std::this_thread::sleep_for(seconds(2));  // past a store flush
  server->Signal(SIGKILL);
  ASSERT_EQ(server->Wait(kDeadline), 128 + SIGKILL);

  auto restarted = Start(server_argv);
  ASSERT_TRUE(restarted->WaitForOutput("restored", kDeadline)) << restarted->Output();
  // Placed by the restarted server (not the frame the dead one published before).
  ASSERT_TRUE(restarted->WaitForOutput("robot beta placed", kDeadline)) << restarted->Output();
  const auto placed = WaitUntilPlaced("beta");
  ASSERT_TRUE(placed && placed->placed()) << restarted->Output();
  ExpectPlacedAt(placed->fleet_from_map, alpha_from_beta_, beta_, 2, *restarted);
  EXPECT_NE(restarted->Output().find("map-frame tiles"), std::string::npos) << restarted->Output();
}

}  // namespace
}  // namespace fleetmap
