// Restart gives the same map (issue 15): real fleetmap-server and fleetmap-agent processes on a
// random domain over loopback. Two robots map overlapping ground, one edits a region and blanks a
// tile; the server is SIGKILLed and restarted on its store, and its fused map must be the map it
// had, cell for cell.

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/scratch_dir.hpp"

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

void Fill(grid::OccupancyGrid* map, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) map->at(x, y) = value;
  }
}

// alpha: 20 x 10 m from the fleet origin, tiles (0, 0) and (1, 0) (10 m tiles, 5 cm cells),
// an unknown strip between them; a wall along y = 5 m in the first, rooms in the second.
grid::OccupancyGrid AlphaMap() {
  grid::OccupancyGrid map(400, 200, 0.05, Pose2{}, grid::kFreeValue);
  Fill(&map, 195, 0, 205, 200, grid::kUnknownValue);
  Fill(&map, 20, 100, 180, 102, grid::kOccupiedValue);
  for (int x = 220; x < 400; x += 40) Fill(&map, x, 20, x + 2, 180, grid::kOccupiedValue);
  return map;
}

// alpha after an edit: a shelf in tile (0, 0), and tile (1, 0) forgotten (all unknown: its agent
// disposes the tile).
grid::OccupancyGrid AlphaEditedMap() {
  grid::OccupancyGrid map = AlphaMap();
  Fill(&map, 140, 80, 142, 130, grid::kOccupiedValue);
  Fill(&map, 195, 0, 400, 200, grid::kUnknownValue);
  return map;
}

// beta, later: the middle band of tile (0, 0), free with a wall along x = 5 m. Where it overlaps
// alpha's older wall, its newer evidence wins.
grid::OccupancyGrid BetaMap() {
  grid::OccupancyGrid map(200, 200, 0.05, Pose2{}, grid::kUnknownValue);
  Fill(&map, 0, 60, 200, 140, grid::kFreeValue);
  Fill(&map, 100, 60, 102, 140, grid::kOccupiedValue);
  return map;
}

// The state of the fleet-frame point `p` in `grid` (unknown outside it).
grid::CellState StateAt(const grid::OccupancyGrid& grid, const Point2& p) {
  const auto cell = grid.CellAt(p);
  return cell ? grid.StateAt(cell->x, cell->y) : grid::CellState::kUnknown;
}

// Cells whose state differs between two fused grids on the same lattice, over both extents.
int64_t DifferingCells(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b) {
  int64_t differing = 0;
  for (const auto* grid : {&a, &b}) {
    const auto* other = grid == &a ? &b : &a;
    for (int y = 0; y < grid->height(); ++y) {
      for (int x = 0; x < grid->width(); ++x) {
        const Point2 p = grid->CellCenter(x, y);
        // Counted once: cells of `b` that `a` also holds were compared from `a`.
        if (grid == &b && a.CellAt(p).has_value()) continue;
        if (grid->StateAt(x, y) != StateAt(*other, p)) ++differing;
      }
    }
  }
  return differing;
}

class StoreRestartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = RandomDomainId();
    env_ = {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  }

  std::unique_ptr<transport::Participant> MakeParticipant() {
    transport::ParticipantOptions options;
    options.domain_id = domain_;
    options.localhost_only = true;
    options.intraprocess_delivery = false;
    auto participant = transport::Participant::Create(options);
    EXPECT_TRUE(participant.ok()) << participant.status();
    return participant.ok() ? std::move(participant).value() : nullptr;
  }

  // Reads rt/fleetmap/map until a grid satisfies `done`, then for `settle` longer; returns the
  // newest grid received.
  std::optional<grid::OccupancyGrid> FleetMap(
      const std::function<bool(const grid::OccupancyGrid&)>& done, milliseconds settle) {
    auto participant = MakeParticipant();
    if (participant == nullptr) return std::nullopt;
    auto wake_up = std::make_shared<WakeUp>();
    auto reader =
        transport::OccupancyGridReader::Create(*participant, transport::kFleetMapTopic, wake_up);
    EXPECT_TRUE(reader.ok()) << reader.status();
    if (!reader.ok()) return std::nullopt;
    std::optional<grid::OccupancyGrid> newest;
    auto deadline = std::chrono::steady_clock::now() + kDeadline;
    bool satisfied = false;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up->WaitFor(milliseconds(100));
      for (auto& map : (*reader)->Drain()) {
        if (map.ok()) newest = std::move(map->grid);
      }
      if (!satisfied && newest && done(*newest)) {
        satisfied = true;
        deadline = std::chrono::steady_clock::now() + settle;
      }
    }
    if (!satisfied && newest) last_unsatisfied_ = newest;
    return satisfied ? newest : std::nullopt;
  }

  // Reads rt/fleetmap/fused_tiles until it has `tiles` tiles, then for `settle` longer; returns
  // the highest revision received of each tile.
  std::map<TileId, uint32_t> FusedRevisions(size_t tiles, milliseconds settle) {
    std::map<TileId, uint32_t> revisions;
    auto participant = MakeParticipant();
    if (participant == nullptr) return revisions;
    auto wake_up = std::make_shared<WakeUp>();
    auto reader =
        transport::VectorTileReader::Create(*participant, transport::kFusedTilesTopic, wake_up);
    EXPECT_TRUE(reader.ok()) << reader.status();
    if (!reader.ok()) return revisions;
    auto deadline = std::chrono::steady_clock::now() + kDeadline;
    bool satisfied = false;
    while (std::chrono::steady_clock::now() < deadline) {
      wake_up->WaitFor(milliseconds(100));
      for (const transport::TileEvent& event : (*reader)->Drain()) {
        if (event.kind != transport::TileEvent::Kind::kTile) continue;
        uint32_t& revision = revisions[event.tile.tile];
        revision = std::max(revision, event.tile.revision);
      }
      if (!satisfied && revisions.size() >= tiles) {
        satisfied = true;
        deadline = std::chrono::steady_clock::now() + settle;
      }
    }
    return revisions;
  }

  // The newest grid of a FleetMap() call that timed out, for the failure message.
  std::optional<grid::OccupancyGrid> last_unsatisfied_;

  std::unique_ptr<Subprocess> StartAgent(const std::string& robot, const std::string& map) {
    auto agent = std::make_unique<Subprocess>(
        std::vector<std::string>{kAgent, "--robot-id", robot, "--map", map}, env_);
    EXPECT_TRUE(agent->started());
    return agent;
  }

  int domain_ = 0;
  std::map<std::string, std::string> env_;
};

TEST_F(StoreRestartTest, KilledServerRestartsToTheSameMapCellForCell) {
  ::fleetmap::testing::ScratchDir dir("store_restart");
  const std::string store = dir.Path("fleet.db");
  const std::string alpha_path = dir.Path("alpha.yaml");
  const std::string beta_path = dir.Path("beta.yaml");
  ASSERT_TRUE(grid::SaveMap(AlphaMap(), alpha_path).ok());
  ASSERT_TRUE(grid::SaveMap(BetaMap(), beta_path).ok());

  auto server = std::make_unique<Subprocess>(
      // Newer evidence winning over a large contradiction is what this test checks survives a
      // restart; quarantine would keep beta's view out (QuarantineTest covers that).
      std::vector<std::string>{kServer, "--store", store, "--no-object-learning",
                               "--no-extrapolation", "--no-quarantine"},
      env_);
  ASSERT_TRUE(server->WaitForOutput("listening", kDeadline)) << server->Output();
  auto alpha = StartAgent("alpha", alpha_path);
  ASSERT_TRUE(alpha->WaitForOutput("map revision 1", kDeadline)) << alpha->Output();
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  // Evidence is dated in tenths of a second: beta's must be clearly newer than alpha's.
  std::this_thread::sleep_for(seconds(1));
  auto beta = StartAgent("beta", beta_path);
  ASSERT_TRUE(beta->WaitForOutput("map revision 1", kDeadline)) << beta->Output();
  ASSERT_TRUE(server->WaitForOutput("robot beta joined", kDeadline)) << server->Output();
  std::this_thread::sleep_for(seconds(1));

  // alpha edits its map: a shelf where beta looked, and its second tile blanked.
  // Saved beside, then renamed over the YAML the agent watches: it never sees half a map.
  const std::string edited_path = dir.Path("alpha_v2.yaml");
  ASSERT_TRUE(grid::SaveMap(AlphaEditedMap(), edited_path).ok());
  std::filesystem::rename(edited_path, alpha_path);
  ASSERT_TRUE(alpha->WaitForOutput("map revision 2", kDeadline)) << alpha->Output();
  const Point2 shelf(7.05, 5.25), alpha_wall_under_beta(3.0, 5.05), blanked(15.0, 5.0);
  const auto before = FleetMap(
      [&](const grid::OccupancyGrid& map) {
        return StateAt(map, shelf) == grid::CellState::kOccupied &&
               StateAt(map, blanked) == grid::CellState::kUnknown;
      },
      seconds(2));
  ASSERT_TRUE(before.has_value())
      << (last_unsatisfied_
              ? "last map: shelf " +
                    std::to_string(static_cast<int>(StateAt(*last_unsatisfied_, shelf))) +
                    ", blanked " +
                    std::to_string(static_cast<int>(StateAt(*last_unsatisfied_, blanked))) + ", " +
                    std::to_string(last_unsatisfied_->width()) + " x " +
                    std::to_string(last_unsatisfied_->height())
              : std::string("no map"))
      << "\n"
      << server->Output() << alpha->Output();
  // What makes the comparison worth doing: alpha's wall under beta's newer view is free, the
  // shelf (alpha's newest evidence) is in, the blanked tile is gone.
  EXPECT_EQ(StateAt(*before, alpha_wall_under_beta), grid::CellState::kFree);
  EXPECT_EQ(StateAt(*before, Point2(5.075, 4.0)), grid::CellState::kOccupied);  // beta's wall

  // The robots go (nothing can re-send their tiles), then the server dies without a word.
  for (auto* agent : {alpha.get(), beta.get()}) {
    agent->Signal(SIGTERM);
    EXPECT_EQ(agent->Wait(kDeadline), 0) << agent->Output();
  }
  std::this_thread::sleep_for(seconds(1));
  server->Signal(SIGKILL);
  ASSERT_EQ(server->Wait(kDeadline), 128 + SIGKILL);
  server.reset();

  Subprocess restarted(
      {kServer, "--store", store, "--no-object-learning", "--no-extrapolation", "--no-quarantine"},
      env_);
  ASSERT_TRUE(restarted.WaitForOutput("restored", kDeadline)) << restarted.Output();
  EXPECT_TRUE(restarted.WaitForOutput("not closed by its last writer", kDeadline))
      << restarted.Output();
  const auto after =
      FleetMap([](const grid::OccupancyGrid& map) { return !map.empty(); }, seconds(2));
  ASSERT_TRUE(after.has_value()) << restarted.Output();
  EXPECT_EQ(DifferingCells(*before, *after), 0)
      << "shelf " << static_cast<int>(StateAt(*after, shelf)) << ", alpha's wall under beta "
      << static_cast<int>(StateAt(*after, alpha_wall_under_beta)) << ", blanked tile "
      << static_cast<int>(StateAt(*after, blanked)) << "\n"
      << restarted.Output();
  EXPECT_EQ(restarted.Output().find("skipping a stored tile"), std::string::npos)
      << restarted.Output();
  restarted.Signal(SIGINT);
  EXPECT_EQ(restarted.Wait(kDeadline), 0) << restarted.Output();
}

TEST_F(StoreRestartTest, WritesThatFailWhileTheStoreIsLockedAreRetriedNotDropped) {
  ::fleetmap::testing::ScratchDir dir("store_restart");
  const std::string store = dir.Path("fleet.db");
  const std::string alpha_path = dir.Path("alpha.yaml");
  ASSERT_TRUE(grid::SaveMap(AlphaMap(), alpha_path).ok());
  auto server = std::make_unique<Subprocess>(
      std::vector<std::string>{kServer, "--store", store, "--no-object-learning",
                               "--no-extrapolation"},
      env_);
  ASSERT_TRUE(server->WaitForOutput("listening", kDeadline)) << server->Output();
  auto alpha = StartAgent("alpha", alpha_path);
  ASSERT_TRUE(alpha->WaitForOutput("map revision 1", kDeadline)) << alpha->Output();
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  std::this_thread::sleep_for(seconds(1));

  // Another program holds the write lock: every write of the server fails (after its 2 s busy
  // timeout) while alpha edits its map.
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(store.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  const std::string edited_path = dir.Path("alpha_v2.yaml");
  ASSERT_TRUE(grid::SaveMap(AlphaEditedMap(), edited_path).ok());
  std::filesystem::rename(edited_path, alpha_path);
  ASSERT_TRUE(alpha->WaitForOutput("map revision 2", kDeadline)) << alpha->Output();
  const bool behind = server->WaitForOutput("map store is behind the fused map", kDeadline);
  sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  ASSERT_TRUE(behind) << server->Output();
  ASSERT_TRUE(server->WaitForOutput("map store caught up after", kDeadline)) << server->Output();

  const Point2 shelf(7.05, 5.25), blanked(15.0, 5.0);
  const auto before = FleetMap(
      [&](const grid::OccupancyGrid& map) {
        return StateAt(map, shelf) == grid::CellState::kOccupied &&
               StateAt(map, blanked) == grid::CellState::kUnknown;
      },
      seconds(1));
  ASSERT_TRUE(before.has_value()) << server->Output();
  alpha->Signal(SIGTERM);
  EXPECT_EQ(alpha->Wait(kDeadline), 0) << alpha->Output();
  std::this_thread::sleep_for(seconds(1));
  server->Signal(SIGKILL);
  ASSERT_EQ(server->Wait(kDeadline), 128 + SIGKILL);
  server.reset();

  Subprocess restarted({kServer, "--store", store, "--no-object-learning", "--no-extrapolation"},
                       env_);
  ASSERT_TRUE(restarted.WaitForOutput("restored", kDeadline)) << restarted.Output();
  const auto after =
      FleetMap([](const grid::OccupancyGrid& map) { return !map.empty(); }, seconds(2));
  ASSERT_TRUE(after.has_value()) << restarted.Output();
  EXPECT_EQ(DifferingCells(*before, *after), 0) << restarted.Output();
  restarted.Signal(SIGINT);
  EXPECT_EQ(restarted.Wait(kDeadline), 0) << restarted.Output();
}

TEST_F(StoreRestartTest, EmptyStoreFileIsRefusedWithHowToStartFresh) {
  ::fleetmap::testing::ScratchDir dir("store_restart");
  const std::string store = dir.Path("fleet.db");
  std::ofstream(store).flush();  // a store truncated to 0 bytes
  Subprocess server({kServer, "--store", store, "--duration", "5"}, env_);
  EXPECT_EQ(server.Wait(kDeadline), 2) << server.Output();
  EXPECT_NE(server.Output().find(store + ": the file is empty (0 bytes)"), std::string::npos)
      << server.Output();
  EXPECT_NE(server.Output().find("To start a new map, delete it"), std::string::npos)
      << server.Output();
  EXPECT_EQ(std::filesystem::file_size(store), 0u);
}

// One writer per store: a second server on a store a running server holds exits 2 naming the
// holder's pid; one started while the holder closes (the restart pattern) waits and takes over.
TEST_F(StoreRestartTest, SecondServerOnAHeldStoreExitsTwoAndAWaitingOneTakesOver) {
  ::fleetmap::testing::ScratchDir dir("store_restart");
  const std::string store = dir.Path("fleet.db");
  const std::vector<std::string> server_args = {kServer, "--store", store, "--no-object-learning",
                                                "--no-extrapolation"};
  Subprocess first(server_args, env_);
  ASSERT_TRUE(first.WaitForOutput("listening", kDeadline)) << first.Output();

  std::vector<std::string> refused_args = server_args;
  refused_args.insert(refused_args.end(), {"--store-lock-timeout", "0"});
  Subprocess refused(refused_args, env_);
  EXPECT_EQ(refused.Wait(kDeadline), 2) << refused.Output();
  EXPECT_NE(refused.Output().find(store + ": the map store is in use by another writer (process " +
                                  std::to_string(first.pid()) + " holds " + store + ".lock)"),
            std::string::npos)
      << refused.Output();
  EXPECT_EQ(refused.Output().find("listening"), std::string::npos) << refused.Output();
  EXPECT_FALSE(first.Wait(std::chrono::milliseconds(0)).has_value());  // undisturbed

  std::vector<std::string> waiting_args = server_args;
  waiting_args.insert(waiting_args.end(), {"--store-lock-timeout", "120"});
  Subprocess waiting(waiting_args, env_);
  ASSERT_TRUE(waiting.WaitForOutput(
      store + " is in use by process " + std::to_string(first.pid()) + ": waiting up to 120 s",
      kDeadline))
      << waiting.Output();
  EXPECT_EQ(waiting.Output().find("listening"), std::string::npos) << waiting.Output();
  first.Signal(SIGINT);
  EXPECT_EQ(first.Wait(kDeadline), 0) << first.Output();
  ASSERT_TRUE(waiting.WaitForOutput("listening", kDeadline)) << waiting.Output();
  EXPECT_NE(waiting.Output().find("closed cleanly"), std::string::npos) << waiting.Output();
  waiting.Signal(SIGINT);
  EXPECT_EQ(waiting.Wait(kDeadline), 0) << waiting.Output();
}

// After a restart, fused tiles go on from the revisions the killed server published (a reader
// keeping the highest revision takes the restarted server's tiles); and a corrupt history BLOB
// is named at start-up while the rest restores.
TEST_F(StoreRestartTest, RestartedServerContinuesRevisionsAndNamesACorruptHistoryBlob) {
  ::fleetmap::testing::ScratchDir dir("store_restart");
  const std::string store = dir.Path("fleet.db");
  const std::string alpha_path = dir.Path("alpha.yaml");
  ASSERT_TRUE(grid::SaveMap(AlphaMap(), alpha_path).ok());
  const std::vector<std::string> server_args = {kServer, "--store", store, "--no-object-learning",
                                                "--no-extrapolation"};
  auto server = std::make_unique<Subprocess>(server_args, env_);
  ASSERT_TRUE(server->WaitForOutput("listening", kDeadline)) << server->Output();
  auto alpha = StartAgent("alpha", alpha_path);
  ASSERT_TRUE(alpha->WaitForOutput("map revision 1", kDeadline)) << alpha->Output();
  ASSERT_TRUE(server->WaitForOutput("robot alpha joined", kDeadline)) << server->Output();
  const std::map<TileId, uint32_t> before = FusedRevisions(2, seconds(2));
  ASSERT_GE(before.size(), 2u) << server->Output();
  alpha->Signal(SIGTERM);
  EXPECT_EQ(alpha->Wait(kDeadline), 0) << alpha->Output();
  std::this_thread::sleep_for(seconds(1));
  server->Signal(SIGKILL);
  ASSERT_EQ(server->Wait(kDeadline), 128 + SIGKILL);
  server.reset();

  // One of alpha's stored revisions goes bad on disk.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(store.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "UPDATE tile_history SET payload = X'00010203deadbeef' WHERE owner = "
                         "'alpha' AND tile_x = 0 AND tile_y = 0",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  EXPECT_EQ(sqlite3_changes(db), 1);
  sqlite3_close(db);

  Subprocess restarted(server_args, env_);
  ASSERT_TRUE(restarted.WaitForOutput("restored", kDeadline)) << restarted.Output();
  EXPECT_NE(restarted.Output().find("skipping a stored tile: " + store +
                                    ": tile_history row of alpha's tile (0, 0) revision 1"),
            std::string::npos)
      << restarted.Output();
  EXPECT_NE(restarted.Output().find("1 corrupt (skipped, named above)"), std::string::npos)
      << restarted.Output();
  const std::map<TileId, uint32_t> after = FusedRevisions(before.size(), seconds(2));
  for (const auto& [tile, revision] : before) {
    ASSERT_EQ(after.count(tile), 1u) << "tile " << tile << " not republished\n"
                                     << restarted.Output();
    EXPECT_GT(after.at(tile), revision) << "tile " << tile;
  }
  restarted.Signal(SIGINT);
  EXPECT_EQ(restarted.Wait(kDeadline), 0) << restarted.Output();
}

}  // namespace
}  // namespace fleetmap
