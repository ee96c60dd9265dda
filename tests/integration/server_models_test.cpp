// The server's models over DDS between real processes: predicted sub-maps from the entities an
// agent publishes, judged against what robots observe later, and movable objects learned from
// the mapping sessions of robots that left. Each test uses its own random domain on loopback.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/extrapolation/entities_json.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

using process::RandomDomainId;
using process::Subprocess;
using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string& kAgent = testing::kAgentBinary;
const std::string& kServer = testing::kServerBinary;
// Bounds for a loaded 2-core CI machine, not assertions about speed.
constexpr seconds kDeadline{40};
constexpr double kResolution = 0.05;

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/server_models_" + std::to_string(getpid()) + "_" + name;
}

std::string SaveGrid(const grid::OccupancyGrid& map, const std::string& name) {
  const std::string path = TempPath(name + ".yaml");
  const Status saved = grid::SaveMap(map, path);
  EXPECT_TRUE(saved.ok()) << saved;
  return path;
}

void Fill(grid::OccupancyGrid& map, double x0, double y0, double x1, double y1, int8_t value) {
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 p = map.CellCenter(x, y);
      if (p.x() >= x0 && p.x() < x1 && p.y() >= y0 && p.y() < y1) map.at(x, y) = value;
    }
  }
}

// A 4 x 4 m room (walls 0.1 m thick) with a closed door in its east wall at y in [1.5, 2.4],
// and east of it, x in [4, 8], a second room: unknown in "before", mapped in "after": empty, or
// packed with shelves (0.1 m thick, 0.1 m apart) when a test wants the prediction to be wrong.
grid::OccupancyGrid TwoRooms(bool after, bool shelves = false) {
  grid::OccupancyGrid map(160, 80, kResolution, Pose2{}, grid::kUnknownValue);
  Fill(map, 0.0, 0.0, 4.05, 4.0, grid::kFreeValue);
  if (after) Fill(map, 4.05, 0.0, 8.0, 4.0, grid::kFreeValue);
  for (double y = 0.0; after && shelves && y < 4.0; y += 0.2) {
    Fill(map, 4.1, y, 8.0, y + 0.1, grid::kOccupiedValue);
  }
  for (const double x : {0.0, 3.95}) Fill(map, x, 0.0, x + 0.1, 4.0, grid::kOccupiedValue);
  Fill(map, 0.0, 0.0, 8.0, 0.1, grid::kOccupiedValue);
  Fill(map, 0.0, 3.9, 8.0, 4.0, grid::kOccupiedValue);
  if (after) Fill(map, 7.9, 0.0, 8.0, 4.0, grid::kOccupiedValue);
  return map;
}

std::string WriteDoorEntities() {
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

class ServerModelsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    auto participant = transport::Participant::Create(options);
    ASSERT_TRUE(participant.ok()) << participant.status();
    participant_ = std::move(participant).value();
  }

  std::unique_ptr<Subprocess> Start(std::vector<std::string> argv) {
    auto process = std::make_unique<Subprocess>(std::move(argv), env_);
    EXPECT_TRUE(process->started());
    return process;
  }

  // Drains `reader` until `done` holds for the latest message of some instance.
  template <typename Reader, typename Message, typename Done>
  std::optional<Message> WaitFor(Reader& reader, WakeUp& wake_up, Done done) {
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up.WaitFor(milliseconds(100));
      for (auto& event : reader.Drain()) {
        EXPECT_NE(event.kind, decltype(event.kind)::kRejected) << event.error;
        if (event.kind != decltype(event.kind)::kSample) continue;
        if constexpr (std::is_same_v<Message, transport::SubmapMessage>) {
          if (event.message.state == scene::SubmapState::kObserved) {
            observed_[event.message.submap.id] = event.message;
          }
        }
        if (done(event.message)) return event.message;
      }
    }
    return std::nullopt;
  }

  // Runs the door scenario: alpha maps the first room and sees the closed door; beta then maps
  // the room behind it. Returns the prediction once it has been judged.
  std::optional<transport::SubmapMessage> JudgedDoorPrediction(bool shelves) {
    auto wake_up = std::make_shared<WakeUp>();
    auto reader = transport::SubmapReader::Create(*participant_, wake_up);
    EXPECT_TRUE(reader.ok()) << reader.status();
    if (!reader.ok()) return std::nullopt;
    auto server = Start({kServer, "--duration", "90", "--map-period", "0.3"});
    auto alpha = Start({kAgent, "--robot-id", "alpha", "--map", SaveGrid(TwoRooms(false), "before"),
                        "--entities", WriteDoorEntities()});
    const auto predicted = WaitFor<transport::SubmapReader, transport::SubmapMessage>(
        **reader, *wake_up, [](const transport::SubmapMessage& message) {
          return message.submap.kind == scene::SubmapKind::kPredictedDoor;
        });
    EXPECT_TRUE(predicted.has_value()) << server->Output();
    if (!predicted) return std::nullopt;
    EXPECT_EQ(predicted->state, scene::SubmapState::kPredicted);
    EXPECT_EQ(predicted->source_robot.value, "alpha");
    EXPECT_EQ(predicted->source_entity, "door_east");
    // Behind the door: the sub-map's frame is east of the door, and it predicts free cells.
    EXPECT_GT(predicted->submap.map_from_submap.x, 4.0);
    EXPECT_GT(predicted->submap.navigable.CountStates().free, 50);
    EXPECT_EQ(predicted->edges.size(), 1u);
    if (!predicted->edges.empty()) {
      EXPECT_EQ(predicted->edges[0].to, 0u);
    }

    auto beta =
        Start({kAgent, "--robot-id", "beta", "--map", SaveGrid(TwoRooms(true, shelves), "after")});
    const uint32_t id = predicted->submap.id;
    auto judged = WaitFor<transport::SubmapReader, transport::SubmapMessage>(
        **reader, *wake_up, [id](const transport::SubmapMessage& message) {
          return message.submap.id == id && message.state != scene::SubmapState::kPredicted;
        });
    EXPECT_TRUE(judged.has_value()) << server->Output();
    server->Signal(SIGINT);
    EXPECT_EQ(server->Wait(kDeadline), 0);
    EXPECT_NE(server->Output().find("extrapolation: 1 entities"), std::string::npos)
        << server->Output();
    return judged;
  }

  int domain_ = 0;
  std::map<std::string, std::string> env_;
  std::unique_ptr<transport::Participant> participant_;
  std::map<uint32_t, transport::SubmapMessage> observed_;  // the latest observed places seen
};

TEST_F(ServerModelsTest, DoorPredictionIsConfirmedWhenTheRoomBehindIsSeenFree) {
  const auto judged = JudgedDoorPrediction(/*shelves=*/false);
  ASSERT_TRUE(judged.has_value());
  EXPECT_EQ(judged->state, scene::SubmapState::kConfirmed);
  EXPECT_GE(judged->precision, 0.9F);
  EXPECT_GE(judged->observed_fraction, 0.5F);
  // Once both rooms are mapped, the door splits the fleet map into two places joined through it.
  ASSERT_EQ(judged->edges.size(), 1u);
  const uint32_t first_room = judged->edges[0].to;
  bool rooms_joined = false;
  for (const auto& [id, place] : observed_) {
    for (const scene::SubmapEdge& edge : place.edges) {
      rooms_joined |= id == first_room && edge.to != id && edge.to < judged->submap.id &&
                      edge.entity_id == "alpha/door_east";
    }
  }
  std::ostringstream seen;
  for (const auto& [id, place] : observed_) {
    for (const scene::SubmapEdge& edge : place.edges) {
      seen << " " << id << "->" << edge.to << " (" << edge.entity_id << ")";
    }
  }
  EXPECT_TRUE(rooms_joined) << observed_.size() << " observed places, first room " << first_room
                            << ", edges:" << seen.str();
}

TEST_F(ServerModelsTest, DoorPredictionIsRetractedWhenShelvesFillTheRoomBehind) {
  const auto judged = JudgedDoorPrediction(/*shelves=*/true);
  ASSERT_TRUE(judged.has_value());
  EXPECT_EQ(judged->state, scene::SubmapState::kRetracted);
  EXPECT_LT(judged->precision, 0.9F);
}

// A 6 x 6 m room with two boxes (0.4 x 0.4 m) that move between sessions.
grid::OccupancyGrid RoomWithBoxes(const std::vector<Point2>& boxes) {
  grid::OccupancyGrid map(120, 120, kResolution, Pose2{}, grid::kFreeValue);
  Fill(map, 0.0, 0.0, 6.0, 0.1, grid::kOccupiedValue);
  Fill(map, 0.0, 5.9, 6.0, 6.0, grid::kOccupiedValue);
  Fill(map, 0.0, 0.0, 0.1, 6.0, grid::kOccupiedValue);
  Fill(map, 5.9, 0.0, 6.0, 6.0, grid::kOccupiedValue);
  for (const Point2& box : boxes) {
    Fill(map, box.x() - 0.2, box.y() - 0.2, box.x() + 0.2, box.y() + 0.2, grid::kOccupiedValue);
  }
  return map;
}

// Whether a fused tile arrives, before `deadline`, with an obstacle vertex near every box: the
// server has fused the current robot's map (the boxes stand elsewhere in every session).
bool FusedTilesShowBoxes(transport::VectorTileReader& fused, WakeUp& wake_up,
                         const std::vector<Point2>& boxes,
                         std::chrono::steady_clock::time_point deadline) {
  while (std::chrono::steady_clock::now() < deadline) {
    wake_up.WaitFor(milliseconds(100));
    for (const transport::TileEvent& event : fused.Drain()) {
      if (event.kind != transport::TileEvent::Kind::kTile) continue;
      bool all = true;
      for (const Point2& box : boxes) {
        bool near = false;
        for (const vector_map::Polyline& polyline : event.tile.map.obstacles) {
          for (const Point2& vertex : polyline.points) near |= (vertex - box).norm() < 0.35;
        }
        all &= near;
      }
      if (all) return true;
    }
  }
  return false;
}

TEST_F(ServerModelsTest, ObjectsAreLearnedFromTheSessionsOfRobotsThatLeft) {
  auto wake_up = std::make_shared<WakeUp>();
  auto templates = transport::ObjectTemplateReader::Create(*participant_, wake_up);
  auto objects = transport::ObjectModelReader::Create(*participant_, wake_up);
  ASSERT_TRUE(templates.ok() && objects.ok());
  const std::string store = TempPath(std::to_string(domain_) + "_store.db");
  std::remove(store.c_str());
  // Each session sees the boxes moved with no other robot there to confirm it: quarantine would
  // hold every later session back until an operator admits it (docs/fleet.md, Quarantine).
  auto server = Start({kServer, "--duration", "120", "--store", store, "--no-quarantine"});
  auto fused_wake_up = std::make_shared<WakeUp>();
  auto fused = transport::VectorTileReader::Create(*participant_, transport::kFusedTilesTopic,
                                                   fused_wake_up);
  ASSERT_TRUE(fused.ok()) << fused.status();
  // Three sessions of one room; the boxes stand somewhere else each time.
  const std::vector<std::vector<Point2>> placements = {
      {{1.5, 1.5}, {4.5, 4.0}}, {{1.0, 4.5}, {3.0, 2.0}}, {{4.5, 1.0}, {2.0, 3.5}}};
  for (size_t t = 0; t < placements.size(); ++t) {
    const std::string robot = "mapper" + std::to_string(t);
    auto agent = Start(
        {kAgent, "--robot-id", robot, "--map", SaveGrid(RoomWithBoxes(placements[t]), robot)});
    ASSERT_TRUE(server->WaitForOutput("robot " + robot + " joined", kDeadline)) << server->Output();
    ASSERT_TRUE(agent->WaitForOutput("changed tiles", kDeadline)) << agent->Output();
    // The session keeps what the server fused: wait for it rather than for a fixed time.
    ASSERT_TRUE(FusedTilesShowBoxes(**fused, *fused_wake_up, placements[t],
                                    std::chrono::steady_clock::now() + kDeadline))
        << server->Output();
    agent->Signal(SIGTERM);
    ASSERT_EQ(agent->Wait(kDeadline), 0);
    ASSERT_TRUE(server->WaitForOutput("mapping session", kDeadline)) << server->Output();
  }
  ASSERT_TRUE(server->WaitForOutput("from 3 sessions", kDeadline)) << server->Output();
  // The newest run's objects and templates (transient local: all of them are there by now).
  std::map<uint32_t, transport::ObjectModelMessage> learned;
  std::map<uint32_t, transport::ObjectTemplateMessage> classes;
  const auto until = std::chrono::steady_clock::now() + seconds(2);
  while (std::chrono::steady_clock::now() < until) {
    wake_up->WaitFor(milliseconds(100));
    for (auto& event : (*objects)->Drain()) {
      if (event.kind == transport::ObjectModelEvent::Kind::kSample) {
        learned[event.message.object_id] = event.message;
      } else if (event.kind == transport::ObjectModelEvent::Kind::kRemoved) {
        learned.erase(event.message.object_id);
      }
    }
    for (auto& event : (*templates)->Drain()) {
      if (event.kind == transport::ObjectTemplateEvent::Kind::kSample) {
        classes[event.message.template_id] = event.message;
      }
    }
  }
  ASSERT_FALSE(learned.empty()) << server->Output();
  ASSERT_FALSE(classes.empty()) << server->Output();
  size_t sightings = 0;
  for (const auto& [id, object] : learned) {
    EXPECT_FALSE(object.patch.empty());
    EXPECT_LT(object.template_id, classes.size());
    // Every sighting is at one of the boxes of its session (sessions are numbered from 1).
    for (const transport::ObjectSighting& sighting : object.sightings) {
      ++sightings;
      ASSERT_GE(sighting.session, 1u);
      ASSERT_LE(sighting.session, placements.size());
      double nearest = INFINITY;
      for (const Point2& box : placements[sighting.session - 1]) {
        nearest = std::min(nearest, (box - sighting.fleet_from_object.translation()).norm());
      }
      EXPECT_LT(nearest, 0.3) << "object " << id << " in session " << sighting.session;
    }
  }
  // Six boxes were seen over the three sessions, each by one snapshot.
  EXPECT_EQ(sightings, 6u) << server->Output();
  server->Signal(SIGINT);
  EXPECT_EQ(server->Wait(kDeadline), 0);
  EXPECT_NE(server->Output().find("object learning: 3 sessions finished"), std::string::npos)
      << server->Output();

  // The sessions are in the store: a restarted server learns again without any robot.
  auto restarted = Start({kServer, "--duration", "60", "--store", store});
  EXPECT_TRUE(restarted->WaitForOutput("from 3 sessions", kDeadline)) << restarted->Output();
  restarted->Signal(SIGINT);
  EXPECT_EQ(restarted->Wait(kDeadline), 0);
  std::remove(store.c_str());
}

}  // namespace
}  // namespace fleetmap
