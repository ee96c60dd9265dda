#include "common/fusion/tile_fusion.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <random>
#include <set>

#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::fusion {
namespace {

using grid::kFreeValue;
using grid::kOccupiedValue;
using grid::kUnknownValue;
using grid::OccupancyGrid;

constexpr double kTileSize = 2.0;  // 40 x 40 cells at 5 cm: small and fast
const Timestamp kT0 = Timestamp(std::chrono::hours(24 * 365 * 54));  // 2024

FusionOptions Options() {
  FusionOptions options;
  options.tile_size = kTileSize;
  options.resolution = 0.05;
  return options;
}

// A fleet-frame grid of `width` x `height` cells from (0, 0), all unknown.
OccupancyGrid Grid(int width, int height) {
  return OccupancyGrid(width, height, 0.05, Pose2{0.0, 0.0, 0.0}, kUnknownValue);
}

void Fill(OccupancyGrid* grid, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) grid->at(x, y) = value;
  }
}

// Vectorizes a robot's fleet-frame grid tile by tile and hands every tile to the fusion.
void Feed(TileFusion* fusion, const std::string& robot, const OccupancyGrid& grid, Timestamp at) {
  vector_map::TiledVectorizeOptions options;
  options.tile_size = kTileSize;
  const auto tiled = vector_map::VectorizeTiled(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  for (const auto& [tile, map] : tiled->tiles) {
    ASSERT_TRUE(fusion->UpdateRobotTile(RobotId{robot}, tile, map, at).ok());
  }
}

int8_t FusedAt(const TileFusion& fusion, int x, int y) { return fusion.FusedGrid().at(x, y); }

TEST(TileFusionTest, OneRobotComesBackThroughFusion) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok()) << fusion.status();
  OccupancyGrid grid = Grid(40, 40);
  Fill(&grid, 2, 2, 38, 38, kFreeValue);
  Fill(&grid, 2, 20, 38, 21, kOccupiedValue);  // a wall across the room
  Feed(&*fusion, "alpha", grid, kT0);
  const auto changed = fusion->FuseChanged();
  ASSERT_TRUE(changed.ok()) << changed.status();
  ASSERT_EQ(changed->size(), 1u);
  EXPECT_EQ((*changed)[0].tile, (TileId{0, 0}));
  EXPECT_EQ((*changed)[0].revision, 1u);
  EXPECT_FALSE((*changed)[0].map.obstacles.empty());
  EXPECT_EQ(FusedAt(*fusion, 10, 20), kOccupiedValue);
  EXPECT_EQ(FusedAt(*fusion, 10, 10), kFreeValue);
  EXPECT_EQ(FusedAt(*fusion, 0, 0), kUnknownValue);
  // Nothing new: nothing to publish.
  EXPECT_TRUE(fusion->FuseChanged()->empty());
}

TEST(TileFusionTest, DisjointViewsAreUnited) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid left = Grid(40, 40);
  Fill(&left, 0, 0, 20, 40, kFreeValue);
  Fill(&left, 5, 5, 6, 30, kOccupiedValue);
  OccupancyGrid right = Grid(40, 40);
  Fill(&right, 20, 0, 40, 40, kFreeValue);
  Fill(&right, 30, 5, 31, 30, kOccupiedValue);
  Feed(&*fusion, "alpha", left, kT0);
  Feed(&*fusion, "beta", right, kT0);
  ASSERT_TRUE(fusion->FuseChanged().ok());
  EXPECT_EQ(FusedAt(*fusion, 5, 15), kOccupiedValue);
  EXPECT_EQ(FusedAt(*fusion, 30, 15), kOccupiedValue);
  EXPECT_EQ(FusedAt(*fusion, 12, 35), kFreeValue);
  EXPECT_EQ(FusedAt(*fusion, 35, 35), kFreeValue);
}

TEST(TileFusionTest, NewerEvidenceWinsAndTiesGoToObstacles) {
  OccupancyGrid closed_door = Grid(40, 40);
  Fill(&closed_door, 0, 0, 40, 40, kFreeValue);
  Fill(&closed_door, 10, 20, 30, 21, kOccupiedValue);
  OccupancyGrid open_door = Grid(40, 40);
  Fill(&open_door, 0, 0, 40, 40, kFreeValue);

  for (const bool open_is_newer : {true, false}) {
    auto fusion = TileFusion::Create(Options());
    ASSERT_TRUE(fusion.ok());
    const Timestamp older = kT0;
    const Timestamp newer = kT0 + std::chrono::seconds(5);
    Feed(&*fusion, "alpha", closed_door, open_is_newer ? older : newer);
    Feed(&*fusion, "beta", open_door, open_is_newer ? newer : older);
    ASSERT_TRUE(fusion->FuseChanged().ok());
    EXPECT_EQ(FusedAt(*fusion, 20, 20), open_is_newer ? kFreeValue : kOccupiedValue)
        << "open is newer: " << open_is_newer;
  }
  auto tie = TileFusion::Create(Options());
  Feed(&*tie, "alpha", closed_door, kT0);
  Feed(&*tie, "beta", open_door, kT0);
  ASSERT_TRUE(tie->FuseChanged().ok());
  EXPECT_EQ(FusedAt(*tie, 20, 20), kOccupiedValue);
}

TEST(TileFusionTest, EvidenceIsDatedPerCellNotPerRevision) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid alpha = Grid(40, 40);
  Fill(&alpha, 0, 0, 40, 40, kFreeValue);  // alpha saw the doorway open at t0
  Feed(&*fusion, "alpha", alpha, kT0);
  OccupancyGrid beta = alpha;
  Fill(&beta, 10, 20, 30, 21, kOccupiedValue);  // beta saw it closed at t0 + 5 s
  Feed(&*fusion, "beta", beta, kT0 + std::chrono::seconds(5));
  ASSERT_TRUE(fusion->FuseChanged().ok());
  ASSERT_EQ(FusedAt(*fusion, 20, 20), kOccupiedValue);
  // alpha republishes at t0 + 10 s because of a change far from the door: its old view of the
  // doorway is not new evidence and must not reopen it.
  Fill(&alpha, 2, 35, 3, 38, kOccupiedValue);
  Feed(&*fusion, "alpha", alpha, kT0 + std::chrono::seconds(10));
  ASSERT_TRUE(fusion->FuseChanged().ok());
  EXPECT_EQ(FusedAt(*fusion, 20, 20), kOccupiedValue);
  EXPECT_EQ(FusedAt(*fusion, 2, 36), kOccupiedValue);
}

TEST(TileFusionTest, WallAcrossABorderMeetsAtTheSamePoint) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid grid = Grid(80, 40);  // tiles (0, 0) and (1, 0)
  Fill(&grid, 0, 0, 80, 40, kFreeValue);
  Fill(&grid, 5, 17, 75, 18, kOccupiedValue);
  Feed(&*fusion, "alpha", grid, kT0);
  const auto changed = fusion->FuseChanged();
  ASSERT_TRUE(changed.ok());
  ASSERT_EQ(changed->size(), 2u);
  const auto& left = fusion->FindFusedTile({0, 0})->map;
  const auto& right = fusion->FindFusedTile({1, 0})->map;
  std::vector<Point2> left_border, right_border;
  for (const auto& polyline : left.obstacles) {
    for (const Point2& p : polyline.points) {
      if (std::abs(p.x() - kTileSize) < 1e-9) left_border.push_back(p);
    }
  }
  for (const auto& polyline : right.obstacles) {
    for (const Point2& p : polyline.points) {
      if (std::abs(p.x() - kTileSize) < 1e-9) right_border.push_back(p);
    }
  }
  ASSERT_EQ(left_border.size(), 1u);
  EXPECT_EQ(left_border, right_border);
}

TEST(TileFusionTest, OnlyTilesNearAChangeAreRevectorized) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid grid = Grid(120, 40);  // tiles (0..2, 0)
  Fill(&grid, 0, 0, 120, 40, kFreeValue);
  Fill(&grid, 10, 10, 110, 11, kOccupiedValue);
  Feed(&*fusion, "alpha", grid, kT0);
  ASSERT_EQ(fusion->FuseChanged()->size(), 3u);
  // A new obstacle in the middle of tile (1, 0), far from its borders.
  Fill(&grid, 58, 25, 62, 29, kOccupiedValue);
  Feed(&*fusion, "alpha", grid, kT0 + std::chrono::seconds(1));
  const auto changed = fusion->FuseChanged();
  ASSERT_TRUE(changed.ok());
  ASSERT_EQ(changed->size(), 1u);
  EXPECT_EQ((*changed)[0].tile, (TileId{1, 0}));
  EXPECT_EQ((*changed)[0].revision, 2u);
}

TEST(TileFusionTest, RemovedContributionDisappears) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid grid = Grid(40, 40);
  Fill(&grid, 0, 0, 40, 40, kFreeValue);
  Feed(&*fusion, "alpha", grid, kT0);
  ASSERT_TRUE(fusion->FuseChanged().ok());
  EXPECT_EQ(fusion->contribution_count(), 1u);
  fusion->RemoveRobotTile(RobotId{"alpha"}, {0, 0});
  ASSERT_TRUE(fusion->FuseChanged().ok());
  EXPECT_EQ(fusion->contribution_count(), 0u);
  EXPECT_EQ(FusedAt(*fusion, 20, 20), kUnknownValue);
}

TEST(TileFusionTest, TileKeysBeyondTheMaximumCoordinateAreRefusedWithTheirKey) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  const vector_map::VectorMap empty;
  const Status far = fusion->UpdateRobotTile(RobotId{"alpha"}, {INT32_MAX, INT32_MAX}, empty, kT0);
  EXPECT_EQ(far.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(far.message(), ::testing::HasSubstr("tile (2147483647, 2147483647) lies"));
  EXPECT_EQ(fusion->contribution_count(), 0u);
}

TEST(TileFusionTest, MapsFarFromTheOriginFuseAndTheirGridIsSmall) {
  // A robot whose map sits 1000 km from the fleet origin (UTM-like coordinates), and one at the
  // origin: the grid for rt/fleetmap/map must not span the 1000 km between them.
  FusionOptions options = Options();
  options.max_grid_cells = 40 * 40 * 16;  // 16 tiles
  auto fusion = TileFusion::Create(options);
  ASSERT_TRUE(fusion.ok());
  OccupancyGrid far(80, 40, 0.05, Pose2{1e6, 1e6, 0.0}, kUnknownValue);
  Fill(&far, 0, 0, 80, 40, kFreeValue);
  Fill(&far, 0, 20, 80, 21, kOccupiedValue);
  vector_map::TiledVectorizeOptions tiling;
  tiling.tile_size = kTileSize;
  const auto tiled = vector_map::VectorizeTiled(far, Transform2::Identity(), tiling);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  for (const auto& [tile, map] : tiled->tiles) {
    ASSERT_TRUE(fusion->UpdateRobotTile(RobotId{"far"}, tile, map, kT0).ok());
  }
  OccupancyGrid near = Grid(40, 40);
  Fill(&near, 0, 0, 40, 40, kFreeValue);
  Feed(&*fusion, "near", near, kT0);
  const auto changed = fusion->FuseChanged();
  ASSERT_TRUE(changed.ok()) << changed.status();
  EXPECT_EQ(changed->size(), 3u);

  GridWindow shown;
  const OccupancyGrid fused = fusion->FusedGrid(&shown);
  // The group that appeared first (the far robot's two tiles) is shown; the tile at the origin
  // is left out.
  EXPECT_EQ(fused.width(), 80);
  EXPECT_EQ(fused.height(), 40);
  EXPECT_NEAR(fused.origin().x, 1e6, 1e-6);
  EXPECT_EQ(shown.tiles_left_out, 1u);
  EXPECT_EQ(fused.at(10, 20), kOccupiedValue);
  EXPECT_EQ(fused.at(70, 5), kFreeValue);
}

// alpha maps a room at t0; beta sees a wall across it at t0 + 5 s; alpha republishes at
// t0 + 10 s for a change in one corner. Per-cell dating keeps beta's wall.
void FeedOverlappingHistory(TileFusion* fusion) {
  OccupancyGrid alpha = Grid(40, 40);
  Fill(&alpha, 0, 0, 40, 40, kFreeValue);
  Feed(fusion, "alpha", alpha, kT0);
  OccupancyGrid beta = Grid(40, 40);
  Fill(&beta, 0, 10, 40, 30, kFreeValue);
  Fill(&beta, 5, 20, 35, 21, kOccupiedValue);
  Feed(fusion, "beta", beta, kT0 + std::chrono::seconds(5));
  Fill(&alpha, 2, 35, 6, 38, kOccupiedValue);
  Feed(fusion, "alpha", alpha, kT0 + std::chrono::seconds(10));
}

TEST(TileFusionTest, ImportedEvidenceRebuildsTheFusionExactly) {
  auto live = TileFusion::Create(Options());
  ASSERT_TRUE(live.ok());
  FeedOverlappingHistory(&*live);
  ASSERT_TRUE(live->FuseChanged().ok());
  ASSERT_EQ(FusedAt(*live, 20, 20), kOccupiedValue);  // beta's wall: newer than alpha's view

  auto restored = TileFusion::Create(Options());
  ASSERT_TRUE(restored.ok());
  for (const std::string robot : {"alpha", "beta"}) {
    std::optional<ContributionEvidence> evidence = live->ExportContribution(RobotId{robot}, {0, 0});
    ASSERT_TRUE(evidence.has_value()) << robot;
    ASSERT_TRUE(restored->ImportContribution(RobotId{robot}, {0, 0}, std::move(*evidence)).ok());
  }
  ASSERT_TRUE(restored->FuseChanged().ok());
  EXPECT_EQ(restored->FusedGrid().data(), live->FusedGrid().data());
  EXPECT_EQ(restored->contribution_count(), 2u);

  // The dates carry on: the same new revision changes both the same way.
  OccupancyGrid alpha = Grid(40, 40);
  Fill(&alpha, 0, 0, 40, 40, kFreeValue);
  Fill(&alpha, 2, 35, 6, 38, kOccupiedValue);
  Fill(&alpha, 30, 2, 34, 6, kOccupiedValue);
  Feed(&*live, "alpha", alpha, kT0 + std::chrono::seconds(20));
  Feed(&*restored, "alpha", alpha, kT0 + std::chrono::seconds(20));
  ASSERT_TRUE(live->FuseChanged().ok());
  ASSERT_TRUE(restored->FuseChanged().ok());
  EXPECT_EQ(restored->FusedGrid().data(), live->FusedGrid().data());
  EXPECT_EQ(FusedAt(*restored, 20, 20), kOccupiedValue);
}

TEST(TileFusionTest, NewestRevisionsAloneDoNotRebuildTheFusion) {
  // What a restart that replays only each tile's newest revision gets: alpha's whole tile dated
  // t0 + 10 s, so its old view of the room erases beta's newer wall. Evidence export exists to
  // avoid exactly this.
  auto live = TileFusion::Create(Options());
  ASSERT_TRUE(live.ok());
  FeedOverlappingHistory(&*live);
  ASSERT_TRUE(live->FuseChanged().ok());
  auto replayed = TileFusion::Create(Options());
  ASSERT_TRUE(replayed.ok());
  OccupancyGrid alpha = Grid(40, 40);
  Fill(&alpha, 0, 0, 40, 40, kFreeValue);
  Fill(&alpha, 2, 35, 6, 38, kOccupiedValue);
  OccupancyGrid beta = Grid(40, 40);
  Fill(&beta, 0, 10, 40, 30, kFreeValue);
  Fill(&beta, 5, 20, 35, 21, kOccupiedValue);
  Feed(&*replayed, "beta", beta, kT0 + std::chrono::seconds(5));
  Feed(&*replayed, "alpha", alpha, kT0 + std::chrono::seconds(10));
  ASSERT_TRUE(replayed->FuseChanged().ok());
  EXPECT_NE(replayed->FusedGrid().data(), live->FusedGrid().data());
  EXPECT_EQ(FusedAt(*replayed, 20, 20), kFreeValue);
}

TEST(TileFusionTest, ExportOfAMissingContributionIsEmpty) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  EXPECT_FALSE(fusion->ExportContribution(RobotId{"alpha"}, {0, 0}).has_value());
  OccupancyGrid grid = Grid(40, 40);
  Fill(&grid, 0, 0, 40, 40, kFreeValue);
  Feed(&*fusion, "alpha", grid, kT0);
  EXPECT_TRUE(fusion->ExportContribution(RobotId{"alpha"}, {0, 0}).has_value());
  EXPECT_FALSE(fusion->ExportContribution(RobotId{"beta"}, {0, 0}).has_value());
  EXPECT_FALSE(fusion->ExportContribution(RobotId{"alpha"}, {1, 0}).has_value());
  fusion->RemoveRobotTile(RobotId{"alpha"}, {0, 0});
  EXPECT_FALSE(fusion->ExportContribution(RobotId{"alpha"}, {0, 0}).has_value());
}

TEST(TileFusionTest, ImportRefusesEvidenceThatDoesNotFitAndChangesNothing) {
  auto fusion = TileFusion::Create(Options());
  ASSERT_TRUE(fusion.ok());
  ContributionEvidence short_evidence{std::vector<int8_t>(10, kFreeValue),
                                      std::vector<uint32_t>(10, 1), kT0};
  const Status wrong_size = fusion->ImportContribution(RobotId{"alpha"}, {0, 0}, short_evidence);
  EXPECT_EQ(wrong_size.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(wrong_size.message(), ::testing::HasSubstr("not 1600"));
  ContributionEvidence bad_value{std::vector<int8_t>(1600, kFreeValue),
                                 std::vector<uint32_t>(1600, 1), kT0};
  bad_value.cells[7] = 42;
  const Status refused = fusion->ImportContribution(RobotId{"alpha"}, {0, 0}, bad_value);
  EXPECT_THAT(refused.message(), ::testing::HasSubstr("cell 7 has value 42"));
  EXPECT_EQ(fusion->contribution_count(), 0u);
}

// The fusion keeps each tile's trusted evidence up to date contribution by contribution
// (NewestEvidence). After every round of random revisions (dates that tie and go back, tiles
// removed, robots of one participant, a robot that erases walls and is quarantined), its fused
// cells equal a fusion built from scratch out of the trusted robots' exported evidence.
TEST(TileFusionTest, IncrementalFusionEqualsTheFusionFromScratch) {
  FusionOptions options = Options();
  options.quarantine.min_contradicted_m = 0.5;
  options.quarantine.max_contradicted_m = 1.0;
  options.quarantine.tolerance_m = 0.1;
  auto live = TileFusion::Create(options);
  ASSERT_TRUE(live.ok());
  const std::vector<std::string> robots = {"alpha", "beta", "gamma", "delta", "liar"};
  live->SetRobotSource(RobotId{"gamma"}, "peer-1");
  live->SetRobotSource(RobotId{"delta"}, "peer-1");
  std::map<std::string, OccupancyGrid> grids;
  for (const std::string& robot : robots) grids.emplace(robot, Grid(80, 80));
  std::set<TileId> tiles_seen;
  std::mt19937 random(3201);
  bool quarantined_once = false;
  for (int round = 0; round < 60; ++round) {
    // Two robots revise their maps: a room seen free, a wall, or (the liar) free over walls.
    for (int n = 0; n < 2; ++n) {
      const std::string& robot = robots[random() % robots.size()];
      OccupancyGrid& grid = grids.at(robot);
      const int x = static_cast<int>(random() % 60);
      const int y = static_cast<int>(random() % 60);
      const int kind = static_cast<int>(random() % 4);
      if (robot == "liar" && round > 20) {
        Fill(&grid, 0, 0, 80, 80, kFreeValue);
      } else if (kind == 0) {
        Fill(&grid, x, y, x + 20, y + 1, kOccupiedValue);
      } else if (kind == 1) {
        Fill(&grid, x, y, x + 20, y + 20, kUnknownValue);
      } else {
        Fill(&grid, x, y, x + 20, y + 20, kFreeValue);
      }
      // Now and then an older stamp than the robot's last (a late revision).
      const Timestamp at = kT0 + std::chrono::seconds(round * 10 - (random() % 5 == 0 ? 15 : 0));
      Feed(&*live, robot, grid, at);
      // A tile stays in the fusion once seen, even when its last contribution goes.
      for (const auto& [contributor, tile] : live->contributions()) tiles_seen.insert(tile);
    }
    if (random() % 8 == 0) {
      live->RemoveRobotTile(RobotId{robots[random() % robots.size()]},
                            TileId{static_cast<int>(random() % 2), static_cast<int>(random() % 2)});
    }
    ASSERT_TRUE(live->FuseChanged().ok());

    FusionOptions plain = options;
    plain.quarantine.enabled = false;
    auto scratch = TileFusion::Create(plain);
    ASSERT_TRUE(scratch.ok());
    // The same tiles, so that both grids cover the same window.
    for (const TileId& tile : tiles_seen) {
      ASSERT_TRUE(scratch
                      ->ImportContribution(RobotId{"nobody"}, tile,
                                           {std::vector<int8_t>(1600, kUnknownValue),
                                            std::vector<uint32_t>(1600, 1), kT0})
                      .ok());
    }
    for (const auto& [robot, tile] : live->contributions()) {
      if (live->TrustOf(robot).standing == Standing::kQuarantined) {
        quarantined_once = true;
        continue;
      }
      std::optional<ContributionEvidence> evidence = live->ExportContribution(robot, tile);
      ASSERT_TRUE(evidence.has_value());
      ASSERT_TRUE(scratch->ImportContribution(robot, tile, std::move(*evidence)).ok());
    }
    ASSERT_TRUE(scratch->FuseChanged().ok());
    ASSERT_EQ(live->FusedGrid().data(), scratch->FusedGrid().data()) << "round " << round;
  }
  EXPECT_TRUE(quarantined_once);
}

TEST(FusionOptionsTest, RejectsBadGeometry) {
  FusionOptions options = Options();
  options.tile_size = -1.0;
  EXPECT_FALSE(TileFusion::Create(options).ok());
  options = Options();
  options.resolution = 0.0;
  EXPECT_FALSE(TileFusion::Create(options).ok());
  options = Options();
  options.resolution = 1.0;  // 2 cells per tile
  EXPECT_THAT(TileFusion::Create(options).status().message(),
              ::testing::HasSubstr("cells per side"));
  options = Options();
  options.resolution = 0.03;  // 66.67 cells: adjusted to whole cells
  EXPECT_NEAR(options.FusedResolution() * options.CellsPerTile(), options.tile_size, 1e-12);
}

}  // namespace
}  // namespace fleetmap::fusion
