#include "server/store_sync.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "common/transport/tile_payload.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::server {
namespace {

using grid::kFreeValue;
using grid::kOccupiedValue;
using grid::kUnknownValue;
using grid::OccupancyGrid;
using ::testing::HasSubstr;
using FlushResult = StoreSync::FlushResult;

constexpr double kTileSize = 2.0;  // 40 x 40 cells at 5 cm
const Timestamp kT0 = Timestamp(std::chrono::hours(24 * 365 * 54));
const auto kNow = std::chrono::steady_clock::time_point(std::chrono::hours(1));

fusion::TileFusion MakeFusion() {
  fusion::FusionOptions options;
  options.tile_size = kTileSize;
  options.resolution = 0.05;
  auto fusion = fusion::TileFusion::Create(options);
  EXPECT_TRUE(fusion.ok()) << fusion.status();
  return std::move(fusion).value();
}

OccupancyGrid Grid(int width, int height, int8_t value = kUnknownValue) {
  return OccupancyGrid(width, height, 0.05, Pose2{0.0, 0.0, 0.0}, value);
}

void Fill(OccupancyGrid* grid, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) grid->at(x, y) = value;
  }
}

// What the fusion worker does with a robot's grid: tile it, fuse each tile, queue each tile
// revision and contribution for the store.
void Publish(fusion::TileFusion* fusion, StoreSync* sync, const std::string& robot,
             const OccupancyGrid& grid, Timestamp stamp, uint32_t revision) {
  vector_map::TiledVectorizeOptions options;
  options.tile_size = kTileSize;
  const auto tiled = vector_map::VectorizeTiled(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  for (const auto& [tile, map] : tiled->tiles) {
    ASSERT_TRUE(fusion->UpdateRobotTile(RobotId{robot}, tile, map, stamp).ok());
    transport::VectorTileMessage message{RobotId{robot}, tile, revision, stamp, kTileSize, map};
    const auto payload = transport::EncodeTilePayload(message);
    ASSERT_TRUE(payload.ok()) << payload.status();
    const int64_t ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(stamp.time_since_epoch()).count();
    ASSERT_TRUE(
        sync->AddTile({store::TileOwner::FromKey(robot), tile, revision, ns, *payload}).ok());
    ASSERT_TRUE(sync->ContributionChanged(RobotId{robot}, tile).ok());
  }
}

// alpha maps two tiles; beta, later, sees a wall across the first; alpha then edits a corner of
// it and blanks the second tile (all unknown: its agent disposes it).
void PlayOverlappingFleet(fusion::TileFusion* fusion, StoreSync* sync) {
  OccupancyGrid alpha = Grid(80, 40, kFreeValue);
  Publish(fusion, sync, "alpha", alpha, kT0, 1);
  OccupancyGrid beta = Grid(40, 40);
  Fill(&beta, 0, 10, 40, 30, kFreeValue);
  Fill(&beta, 5, 20, 35, 21, kOccupiedValue);
  Publish(fusion, sync, "beta", beta, kT0 + std::chrono::seconds(5), 1);
  Fill(&alpha, 2, 35, 6, 38, kOccupiedValue);
  Fill(&alpha, 40, 0, 80, 40, kUnknownValue);
  Publish(fusion, sync, "alpha", alpha, kT0 + std::chrono::seconds(10), 2);
  fusion->RemoveRobotTile(RobotId{"alpha"}, {1, 0});
  ASSERT_TRUE(sync->ContributionChanged(RobotId{"alpha"}, {1, 0}).ok());
}

// The fused cells of tile (0, 0), the first tile of every grid here.
std::vector<int8_t> FirstTileCells(const fusion::TileFusion& fusion) {
  const OccupancyGrid grid = fusion.FusedGrid();
  std::vector<int8_t> cells;
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) cells.push_back(grid.at(x, y));
  }
  return cells;
}

std::unique_ptr<store::MapStore> OpenStore(const std::string& path,
                                           const store::StoreOptions& options = {}) {
  auto store = store::MapStore::Open(path, options);
  EXPECT_TRUE(store.ok()) << store.status();
  return store.ok() ? std::move(store).value() : nullptr;
}

void ExecRaw(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error != nullptr ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

TEST(StoreSyncTest, RestartRebuildsTheFusedMapCellForCell) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  fusion::TileFusion live = MakeFusion();
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    StoreSync sync(store.get(), {});
    PlayOverlappingFleet(&live, &sync);
    ASSERT_TRUE(live.FuseChanged().ok());
    ASSERT_EQ(sync.Flush(live, kNow), FlushResult::kWritten) << sync.last_error();
    EXPECT_EQ(sync.pending(), 0u);
    // The blanked tile left the store; the others' evidence is there.
    EXPECT_EQ(store->LatestTiles(store::TileOwner::FromKey("alpha"))->size(), 1u);
    EXPECT_EQ(store->Evidence()->size(), 2u);
  }
  ASSERT_EQ(live.FusedGrid().at(20, 20), kOccupiedValue);  // beta's newer wall

  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion restored = MakeFusion();
  const auto result = sync.Restore(&restored);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->from_evidence, 2u);
  EXPECT_EQ(result->from_history, 0u);
  EXPECT_TRUE(result->skipped.empty());
  ASSERT_TRUE(restored.FuseChanged().ok());
  EXPECT_EQ(restored.contribution_count(), live.contribution_count());
  EXPECT_EQ(restored.FindFusedTile({1, 0}), nullptr);
  ASSERT_EQ(restored.FindFusedTile({0, 0}) != nullptr, true);
  // Tile (0, 0), cell for cell (tile (1, 0) is unknown in both).
  EXPECT_EQ(FirstTileCells(restored), FirstTileCells(live));
  const OccupancyGrid a = live.FusedGrid();
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 40; x < a.width(); ++x) ASSERT_EQ(a.at(x, y), kUnknownValue);
  }
  EXPECT_EQ(restored.FindFusedTile({0, 0})->map.obstacles,
            live.FindFusedTile({0, 0})->map.obstacles);
}

TEST(StoreSyncTest, OlderStoreIsRebuiltFromItsHistoryInOrderAndUpgraded) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  fusion::TileFusion live = MakeFusion();
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    StoreSync sync(store.get(), {});
    PlayOverlappingFleet(&live, &sync);
    ASSERT_EQ(sync.Flush(live, kNow), FlushResult::kWritten);
  }
  ASSERT_TRUE(live.FuseChanged().ok());
  // A version 2 store: revisions and history, no evidence.
  ExecRaw(path,
          "DROP TABLE tile_evidence; DROP TABLE store_state; DROP TABLE admissions; "
          "PRAGMA user_version = 2");
  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion restored = MakeFusion();
  const auto result = sync.Restore(&restored);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->from_history, 2u);
  ASSERT_TRUE(restored.FuseChanged().ok());
  EXPECT_EQ(FirstTileCells(restored), FirstTileCells(live));
  // The first flush gives the store the evidence it lacked.
  EXPECT_EQ(sync.Flush(restored, kNow), FlushResult::kWritten);
  EXPECT_EQ(store->Evidence()->size(), 2u);
}

TEST(StoreSyncTest, RowWhoseKeyDisagreesWithItsPayloadIsSkipped) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    vector_map::VectorMap map;
    map.epsilon = 0.0707;
    map.obstacles.push_back({{Point2(0.2, 1.0), Point2(1.8, 1.0)}, false, 0.0});
    const auto tile_0_0 = transport::EncodeTilePayload({"alpha", {0, 0}, 1, kT0, kTileSize, map});
    ASSERT_TRUE(tile_0_0.ok()) << tile_0_0.status();
    // The payload of tile (0, 0) under a key 2000 Mm away (its cells beyond the int range: fused
    // there, start-up spun at 100 % CPU), another under beta's name; and one good row.
    ASSERT_TRUE(store
                    ->PutTiles({{store::TileOwner::FromKey("alpha"), {1 << 30, 0}, 1, 1, *tile_0_0},
                                {store::TileOwner::FromKey("beta"), {0, 0}, 1, 1, *tile_0_0},
                                {store::TileOwner::FromKey("alpha"), {0, 0}, 1, 1, *tile_0_0}})
                    .ok());
  }
  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion restored = MakeFusion();
  const auto result = sync.Restore(&restored);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->from_history, 1u);
  // Each bad row is named once per table that holds it: its latest row and its history row.
  ASSERT_EQ(result->skipped.size(), 4u);
  EXPECT_EQ(result->corrupt_rows, 4u);
  EXPECT_EQ(result->tile_rows_checked, 6u);
  EXPECT_THAT(result->skipped[0],
              HasSubstr("tile_latest row of alpha's tile (1073741824, 0) revision 1: its payload "
                        "is alpha's tile (0, 0)"));
  EXPECT_THAT(result->skipped[1], HasSubstr("its payload is alpha's tile (0, 0), not the row's"));
  EXPECT_THAT(result->skipped[2],
              HasSubstr("tile_history row of alpha's tile (1073741824, 0) revision 1"));
  EXPECT_THAT(result->skipped[3], HasSubstr("tile_history row of beta's tile (0, 0) revision 1"));
  EXPECT_EQ(restored.contribution_count(), 1u);
}

TEST(StoreSyncTest, DamagedEvidenceIsSkippedWithItsReason) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    ASSERT_TRUE(
        store
            ->Write({{},
                     {{RobotId{"alpha"}, {0, 0}, 1, "garbage"}, {RobotId{"fleet"}, {0, 0}, 1, ""}},
                     {},
                     {}})
            .ok());
  }
  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion restored = MakeFusion();
  const auto result = sync.Restore(&restored);
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->skipped.size(), 2u);
  EXPECT_THAT(result->skipped[0], HasSubstr("not fleetmap tile evidence"));
  EXPECT_THAT(result->skipped[1], HasSubstr("the fleet owns no evidence"));
  EXPECT_EQ(restored.contribution_count(), 0u);
}

TEST(StoreSyncTest, DiskFullKeepsTheNewestOfEachTileAndCatchesUpWhenSpaceReturns) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  store::StoreOptions options;
  options.max_page_count = 60;  // 240 KB
  auto store = OpenStore(path, options);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), StoreSync::Options{std::chrono::milliseconds(1000)});
  fusion::TileFusion fusion = MakeFusion();
  const std::string filler(2000, 'x');
  uint32_t revision = 0;
  auto now = kNow;
  // Revisions of 8 tiles until the file is full.
  FlushResult result = FlushResult::kWritten;
  while (result == FlushResult::kWritten && revision < 1000) {
    ++revision;
    for (int x = 0; x < 8; ++x) {
      ASSERT_TRUE(
          sync.AddTile({store::TileOwner::FromKey("alpha"), {x, 0}, revision, revision, filler})
              .ok());
    }
    result = sync.Flush(fusion, now);
  }
  ASSERT_EQ(result, FlushResult::kFailed);
  EXPECT_TRUE(sync.behind());
  EXPECT_EQ(sync.last_error().code(), StatusCode::kResourceExhausted) << sync.last_error();
  EXPECT_EQ(sync.pending(), 8u);
  const uint32_t failed_at = revision;

  // Behind: more revisions of the same tiles replace those waiting; nothing is tried before the
  // retry period.
  for (int more = 0; more < 50; ++more) {
    ++revision;
    for (int x = 0; x < 8; ++x) {
      ASSERT_TRUE(
          sync.AddTile({store::TileOwner::FromKey("alpha"), {x, 0}, revision, revision, filler})
              .ok());
    }
  }
  EXPECT_EQ(sync.pending(), 8u);
  EXPECT_EQ(sync.Flush(fusion, now + std::chrono::milliseconds(10)), FlushResult::kWaiting);
  now += std::chrono::milliseconds(1000);
  EXPECT_EQ(sync.Flush(fusion, now), FlushResult::kFailed);  // still full
  EXPECT_EQ(sync.failed_attempts(), 2u);

  // Space comes back (history dropped by another connection): the next attempt writes the newest
  // revision of every tile.
  ExecRaw(path, "DELETE FROM tile_history");
  now += std::chrono::milliseconds(1000);
  ASSERT_EQ(sync.Flush(fusion, now), FlushResult::kWritten) << sync.last_error();
  EXPECT_FALSE(sync.behind());
  EXPECT_EQ(sync.pending(), 0u);
  const auto latest = store->LatestTiles(store::TileOwner::FromKey("alpha"));
  ASSERT_TRUE(latest.ok());
  ASSERT_EQ(latest->size(), 8u);
  for (const store::TileRecord& tile : *latest) EXPECT_EQ(tile.revision, revision);
  EXPECT_GT(revision, failed_at);
}

TEST(StoreSyncTest, RecordsTheStoreWouldRefuseAreRefusedAlone) {
  testing::ScratchDir dir("store_sync");
  auto store = OpenStore(dir.Path("store.db"));
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion fusion = MakeFusion();
  EXPECT_EQ(sync.AddTile({store::TileOwner::FromKey(""), {0, 0}, 1, 1, "x"}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(sync.AddTile({store::TileOwner::FromKey("alpha"), {0, 0}, 1, -5, "x"}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(sync.ContributionChanged(RobotId{"no good"}, {0, 0}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(sync.AddRobot({"alpha", 5, 1, "active", ""}).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(sync.AddTile({store::TileOwner::FromKey("alpha"), {0, 0}, 1, 1, "x"}).ok());
  EXPECT_EQ(sync.Flush(fusion, kNow), FlushResult::kWritten) << sync.last_error();
  EXPECT_EQ(store->LatestTiles()->size(), 1u);
}

TEST(StoreSyncTest, FusedRevisionsGoOnFromTheStoredOnesAfterARestart) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    vector_map::VectorMap map;
    map.epsilon = 0.0707;
    const auto fused =
        transport::EncodeTilePayload({RobotId{"fleet"}, {0, 0}, 7, kT0, kTileSize, map});
    ASSERT_TRUE(fused.ok()) << fused.status();
    ASSERT_TRUE(store->PutTiles({{store::TileOwner::FromKey("fleet"), {0, 0}, 7, 1, *fused}}).ok());
  }
  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion fusion = MakeFusion();
  const auto result = sync.Restore(&fusion);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_TRUE(result->skipped.empty());
  // A robot maps tile (0, 0), which the last process had fused up to revision 7, and a new one.
  Publish(&fusion, &sync, "alpha", Grid(80, 40, kFreeValue), kT0, 1);
  const auto changed = fusion.FuseChanged();
  ASSERT_TRUE(changed.ok()) << changed.status();
  ASSERT_NE(fusion.FindFusedTile({0, 0}), nullptr);
  ASSERT_NE(fusion.FindFusedTile({1, 0}), nullptr);
  EXPECT_EQ(fusion.FindFusedTile({0, 0})->revision, 8u);
  EXPECT_EQ(fusion.FindFusedTile({1, 0})->revision, 1u);
  // Stored as published: the store's latest fused row is the new one.
  ASSERT_TRUE(sync.AddTile({store::TileOwner::FromKey("fleet"), {0, 0}, 8, 2, "eight"}).ok());
  ASSERT_EQ(sync.Flush(fusion, kNow), FlushResult::kWritten);
  const auto latest = store->LatestTiles(store::TileOwner::FromKey("fleet"));
  ASSERT_TRUE(latest.ok());
  ASSERT_EQ(latest->size(), 1u);
  EXPECT_EQ((*latest)[0], (store::TileRecord{store::TileOwner::Fleet(), {0, 0}, 8, 2, "eight"}));
}

// A corrupt history BLOB (the restore from evidence never reads it) is named at start-up by its
// owner, tile and revision; everything else restores.
TEST(StoreSyncTest, CorruptHistoryBlobIsNamedAndTheRestRestores) {
  testing::ScratchDir dir("store_sync");
  const std::string path = dir.Path("store.db");
  fusion::TileFusion live = MakeFusion();
  {
    auto store = OpenStore(path);
    ASSERT_NE(store, nullptr);
    StoreSync sync(store.get(), {});
    PlayOverlappingFleet(&live, &sync);
    ASSERT_EQ(sync.Flush(live, kNow), FlushResult::kWritten) << sync.last_error();
  }
  ASSERT_TRUE(live.FuseChanged().ok());
  ExecRaw(path,
          "UPDATE tile_history SET payload = X'00010203deadbeef' WHERE owner = 'alpha' AND "
          "tile_x = 0 AND tile_y = 0 AND revision = 1");
  auto store = OpenStore(path);
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion restored = MakeFusion();
  const auto result = sync.Restore(&restored);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->corrupt_rows, 1u);
  ASSERT_EQ(result->skipped.size(), 1u);
  EXPECT_THAT(result->skipped[0],
              HasSubstr(path + ": tile_history row of alpha's tile (0, 0) revision 1"));
  EXPECT_EQ(result->from_evidence, 2u);
  ASSERT_TRUE(restored.FuseChanged().ok());
  EXPECT_EQ(FirstTileCells(restored), FirstTileCells(live));
}

TEST(StoreSyncTest, RobotRecordsAreMergedWhileWaiting) {
  testing::ScratchDir dir("store_sync");
  auto store = OpenStore(dir.Path("store.db"));
  ASSERT_NE(store, nullptr);
  StoreSync sync(store.get(), {});
  fusion::TileFusion fusion = MakeFusion();
  ASSERT_TRUE(sync.AddRobot({"alpha", 10, 20, "active", "a"}).ok());
  ASSERT_TRUE(sync.AddRobot({"alpha", 15, 30, "lost", "b"}).ok());
  EXPECT_EQ(sync.pending(), 1u);
  ASSERT_EQ(sync.Flush(fusion, kNow), FlushResult::kWritten);
  const auto robots = store->Robots();
  ASSERT_TRUE(robots.ok());
  ASSERT_EQ(robots->size(), 1u);
  EXPECT_EQ((*robots)[0], (store::RobotRecord{"alpha", 10, 30, "lost", "b"}));
  EXPECT_EQ(sync.Flush(fusion, kNow), FlushResult::kIdle);
}

}  // namespace
}  // namespace fleetmap::server
