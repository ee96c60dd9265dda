// Contradiction quarantine in TileFusion (docs/fleet.md, "Quarantine"): a robot whose map calls
// free what the fleet established as walls is kept out of the fused map until it agrees again,
// another participant's robot confirms the change, or an operator admits it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "common/fusion/tile_fusion.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::fusion {
namespace {

using grid::kFreeValue;
using grid::kOccupiedValue;
using grid::kUnknownValue;
using grid::OccupancyGrid;

constexpr double kTileSize = 2.0;
constexpr int kSide = 240;  // 12 m of fleet frame at 5 cm
const Timestamp kT0 = Timestamp(std::chrono::hours(24 * 365 * 54));

TileFusion MakeFusion() {
  FusionOptions options;
  options.tile_size = kTileSize;
  options.resolution = 0.05;
  auto fusion = TileFusion::Create(options);
  EXPECT_TRUE(fusion.ok()) << fusion.status();
  return std::move(fusion).value();
}

void Fill(OccupancyGrid* grid, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = std::max(0, y0); y < std::min(grid->height(), y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(grid->width(), x1); ++x) grid->at(x, y) = value;
  }
}

void Outline(OccupancyGrid* grid, int x0, int y0, int x1, int y1) {
  Fill(grid, x0, y0, x1, y0 + 1, kOccupiedValue);
  Fill(grid, x0, y1 - 1, x1, y1, kOccupiedValue);
  Fill(grid, x0, y0, x0 + 1, y1, kOccupiedValue);
  Fill(grid, x1 - 1, y0, x1, y1, kOccupiedValue);
}

// An 8 m room (cells 20..180) with a wall halfway across it, shifted by (dx, dy) cells; with
// `shelves`, three rows of shelves (outlines, 1.5 m x 0.3 m) in its left half.
OccupancyGrid Room(int dx = 0, int dy = 0, bool shelves = false) {
  OccupancyGrid grid(kSide, kSide, 0.05, Pose2{}, kUnknownValue);
  Fill(&grid, 20 + dx, 20 + dy, 180 + dx, 180 + dy, kFreeValue);
  Outline(&grid, 20 + dx, 20 + dy, 180 + dx, 180 + dy);
  Fill(&grid, 100 + dx, 20 + dy, 101 + dx, 120 + dy, kOccupiedValue);
  if (shelves) {
    for (const int y : {50, 80, 110}) Outline(&grid, 40 + dx, y + dy, 70 + dx, y + 6 + dy);
  }
  return grid;
}

// `grid` turned by `degrees` about the room's centre (nearest cell).
OccupancyGrid Turned(const OccupancyGrid& grid, double degrees) {
  OccupancyGrid out(kSide, kSide, 0.05, Pose2{}, kUnknownValue);
  const double a = degrees * std::numbers::pi / 180.0;
  const double c = 100.0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      // The source cell of (x, y): turned back by -a.
      const double sx = std::cos(a) * (x - c) + std::sin(a) * (y - c) + c;
      const double sy = -std::sin(a) * (x - c) + std::cos(a) * (y - c) + c;
      const int ix = static_cast<int>(std::lround(sx));
      const int iy = static_cast<int>(std::lround(sy));
      if (ix >= 0 && iy >= 0 && ix < kSide && iy < kSide) out.at(x, y) = grid.at(ix, iy);
    }
  }
  return out;
}

void Feed(TileFusion* fusion, const std::string& robot, const OccupancyGrid& grid, Timestamp at) {
  vector_map::TiledVectorizeOptions options;
  options.tile_size = kTileSize;
  const auto tiled = vector_map::VectorizeTiled(grid, Transform2::Identity(), options);
  ASSERT_TRUE(tiled.ok()) << tiled.status();
  for (const auto& [tile, map] : tiled->tiles) {
    ASSERT_TRUE(fusion->UpdateRobotTile(RobotId{robot}, tile, map, at).ok());
  }
}

void Fuse(TileFusion* fusion) {
  const auto changed = fusion->FuseChanged();
  ASSERT_TRUE(changed.ok()) << changed.status();
}

// The fused cells on the fixed 12 m lattice from the origin (FusedGrid() spans the tiles only).
OccupancyGrid Fused(const TileFusion& fusion) {
  const OccupancyGrid fused = fusion.FusedGrid();
  OccupancyGrid out(kSide, kSide, 0.05, Pose2{}, kUnknownValue);
  const int ox = static_cast<int>(std::lround(fused.origin().x / 0.05));
  const int oy = static_cast<int>(std::lround(fused.origin().y / 0.05));
  for (int y = 0; y < fused.height(); ++y) {
    for (int x = 0; x < fused.width(); ++x) {
      if (x + ox >= 0 && y + oy >= 0 && x + ox < kSide && y + oy < kSide) {
        out.at(x + ox, y + oy) = fused.at(x, y);
      }
    }
  }
  return out;
}

// Occupied cells of `before` that `after` no longer calls occupied.
int ErasedWalls(const OccupancyGrid& before, const OccupancyGrid& after) {
  int erased = 0;
  for (size_t i = 0; i < before.data().size(); ++i) {
    erased += before.data()[i] == kOccupiedValue && after.data()[i] != kOccupiedValue;
  }
  return erased;
}

int Count(const OccupancyGrid& grid, int8_t value) {
  return static_cast<int>(std::count(grid.data().begin(), grid.data().end(), value));
}

// alpha maps the room at t0; its fused cells.
OccupancyGrid Establish(TileFusion* fusion, bool shelves = false) {
  Feed(fusion, "alpha", Room(0, 0, shelves), kT0);
  Fuse(fusion);
  return Fused(*fusion);
}

TEST(QuarantineTest, AFreshIdPaintingFreeOverTheWallsErasesNothing) {
  TileFusion fusion = MakeFusion();
  const OccupancyGrid before = Establish(&fusion);
  ASSERT_GT(Count(before, kOccupiedValue), 600);
  OccupancyGrid all_free(kSide, kSide, 0.05, Pose2{}, kFreeValue);
  Feed(&fusion, "mallory", all_free, kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  const OccupancyGrid after = Fused(fusion);
  EXPECT_EQ(ErasedWalls(before, after), 0);
  EXPECT_EQ(Count(after, kFreeValue), Count(before, kFreeValue)) << "unknown painted free";
  const TrustReport report = fusion.TrustOf(RobotId{"mallory"});
  EXPECT_EQ(report.standing, Standing::kQuarantined);
  EXPECT_GT(report.share, 0.9);
  EXPECT_NE(report.reason.find("walls other robots established"), std::string::npos);
  EXPECT_LE(report.area_min.x(), 1.05);
  EXPECT_GE(report.area_max.x(), 8.95);
  const std::vector<TrustReport> changes = fusion.TakeTrustChanges();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].robot, RobotId{"mallory"});
  EXPECT_TRUE(fusion.TakeTrustChanges().empty());
  // Its tiles are kept (a store keeps them, an operator may admit it).
  EXPECT_TRUE(fusion.ExportContribution(RobotId{"mallory"}, TileId{2, 2}).has_value());
}

TEST(QuarantineTest, AQuarantinedRobotsFiguresFollowItsLaterTiles) {
  TileFusion fusion = MakeFusion();
  Establish(&fusion);
  // mallory's map reaches the server in two parts: the left of the room, then the right.
  OccupancyGrid left(kSide, kSide, 0.05, Pose2{}, kUnknownValue);
  Fill(&left, 0, 0, 80, kSide, kFreeValue);
  Feed(&fusion, "mallory", left, kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  const std::vector<TrustReport> entered = fusion.TakeTrustChanges();
  ASSERT_EQ(entered.size(), 1u);
  ASSERT_EQ(entered[0].standing, Standing::kQuarantined);
  EXPECT_TRUE(entered[0].standing_changed);

  OccupancyGrid all_free(kSide, kSide, 0.05, Pose2{}, kFreeValue);
  Feed(&fusion, "mallory", all_free, kT0 + std::chrono::seconds(20));
  Fuse(&fusion);
  const std::vector<TrustReport> moved = fusion.TakeTrustChanges();
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_EQ(moved[0].standing, Standing::kQuarantined);
  EXPECT_FALSE(moved[0].standing_changed);
  EXPECT_GT(moved[0].contradicted_m, 1.5 * entered[0].contradicted_m);
  EXPECT_GT(moved[0].area_max.x(), entered[0].area_max.x() + 2.0);
  // Nothing moved since: nothing to report.
  Feed(&fusion, "mallory", all_free, kT0 + std::chrono::seconds(30));
  Fuse(&fusion);
  EXPECT_TRUE(fusion.TakeTrustChanges().empty());
}

TEST(QuarantineTest, AnHonestSecondViewOfTheRoomIsFused) {
  TileFusion fusion = MakeFusion();
  const OccupancyGrid before = Establish(&fusion);
  Feed(&fusion, "beta", Room(1, 0), kT0 + std::chrono::seconds(10));  // 5 cm off: noise
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kTrusted);
  EXPECT_TRUE(fusion.TakeTrustChanges().empty());
}

TEST(QuarantineTest, ARobotShiftedTwoMetresIsQuarantined) {
  TileFusion fusion = MakeFusion();
  const OccupancyGrid before = Establish(&fusion);
  Feed(&fusion, "beta", Room(40, 0), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  EXPECT_EQ(ErasedWalls(before, Fused(fusion)), 0);
}

TEST(QuarantineTest, ARobotTurnedTenDegreesIsQuarantined) {
  TileFusion fusion = MakeFusion();
  const OccupancyGrid before = Establish(&fusion);
  Feed(&fusion, "beta", Turned(Room(), 10.0), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  EXPECT_EQ(ErasedWalls(before, Fused(fusion)), 0);
}

TEST(QuarantineTest, ARelocalizedRobotLeavesQuarantineAndIsFused) {
  TileFusion fusion = MakeFusion();
  Establish(&fusion);
  Feed(&fusion, "beta", Room(40, 0), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  ASSERT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  fusion.TakeTrustChanges();
  // Relocalized: its SLAM republishes the map where it belongs; the tiles it left are disposed.
  for (const auto& [robot, tile] : fusion.contributions()) {
    if (robot == RobotId{"beta"}) fusion.RemoveRobotTile(robot, tile);
  }
  OccupancyGrid right = Room();
  Outline(&right, 150, 150, 170, 170);  // and something new it found
  Feed(&fusion, "beta", right, kT0 + std::chrono::seconds(20));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kTrusted);
  EXPECT_EQ(Fused(fusion).at(150, 160), kOccupiedValue);
  const std::vector<TrustReport> changes = fusion.TakeTrustChanges();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_NE(changes[0].reason.find("agrees"), std::string::npos);
}

TEST(QuarantineTest, ASmallRealChangeIsFusedAtOnce) {
  TileFusion fusion = MakeFusion();
  Establish(&fusion);
  OccupancyGrid opened = Room();
  Fill(&opened, 100, 60, 101, 80, kFreeValue);  // a 1 m door in the inner wall, now open
  Feed(&fusion, "beta", opened, kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kTrusted);
  EXPECT_EQ(Fused(fusion).at(100, 70), kFreeValue);
}

TEST(QuarantineTest, ALargeChangeWaitsForAnotherParticipantsRobotToConfirmIt) {
  TileFusion fusion = MakeFusion();
  const OccupancyGrid before = Establish(&fusion, /*shelves=*/true);
  ASSERT_EQ(before.at(40, 50), kOccupiedValue);
  fusion.SetRobotSource(RobotId{"beta"}, "participant-b");
  fusion.SetRobotSource(RobotId{"gamma"}, "participant-g");
  // The shelves were taken away: beta alone says so, over 10 m of established walls.
  Feed(&fusion, "beta", Room(), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  ASSERT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  EXPECT_EQ(Fused(fusion).at(40, 50), kOccupiedValue);
  // gamma, another participant's robot, sees the same: the change is real.
  Feed(&fusion, "gamma", Room(), kT0 + std::chrono::seconds(12));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"gamma"}).standing, Standing::kTrusted);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kTrusted);
  const OccupancyGrid after = Fused(fusion);
  EXPECT_NE(after.at(40, 50), kOccupiedValue);
  EXPECT_NE(after.at(55, 80), kOccupiedValue);
  EXPECT_EQ(after.at(20, 100), kOccupiedValue);  // the room's walls stay
}

TEST(QuarantineTest, RobotsOfOneParticipantDoNotConfirmEachOther) {
  TileFusion fusion = MakeFusion();
  Establish(&fusion, /*shelves=*/true);
  fusion.SetRobotSource(RobotId{"beta"}, "participant-b");
  fusion.SetRobotSource(RobotId{"beta2"}, "participant-b");
  Feed(&fusion, "beta", Room(), kT0 + std::chrono::seconds(10));
  Feed(&fusion, "beta2", Room(), kT0 + std::chrono::seconds(12));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta2"}).standing, Standing::kQuarantined);
  EXPECT_EQ(Fused(fusion).at(40, 50), kOccupiedValue);
}

// The shelf rows of Room(0, 0, true) alone, in space otherwise unknown: walls nobody else saw.
OccupancyGrid PhantomShelves() {
  OccupancyGrid phantom(kSide, kSide, 0.05, Pose2{}, kUnknownValue);
  for (const int y : {50, 80, 110}) Outline(&phantom, 40, y, 70, y + 6);
  return phantom;
}

// Walls that a robot lost in its localization (or a peer) paints in space nobody had seen yet
// come first; the robots that map that space next see it free. Two robots of other participants
// that agree elsewhere are corroborated, and uncorroborated walls never quarantine them.
TEST(QuarantineTest, UncorroboratedWallsInUnseenSpaceDoNotQuarantineCorroboratedRobots) {
  TileFusion fusion = MakeFusion();
  fusion.SetRobotSource(RobotId{"lost"}, "participant-l");
  fusion.SetRobotSource(RobotId{"alpha"}, "participant-a");
  fusion.SetRobotSource(RobotId{"beta"}, "participant-b");
  Feed(&fusion, "lost", PhantomShelves(), kT0);
  Fuse(&fusion);
  ASSERT_EQ(Fused(fusion).at(40, 50), kOccupiedValue);
  // alpha maps the whole room; beta only its right half, which alpha's walls agree with.
  OccupancyGrid right_half = Room();
  Fill(&right_half, 0, 0, 95, kSide, kUnknownValue);
  Feed(&fusion, "alpha", Room(), kT0 + std::chrono::seconds(10));
  Feed(&fusion, "beta", right_half, kT0 + std::chrono::seconds(12));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"alpha"}).standing, Standing::kTrusted)
      << fusion.TrustOf(RobotId{"alpha"}).reason;
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kTrusted);
  // alpha's newer free space wins over the phantom shelves; the room's walls stay.
  const OccupancyGrid after = Fused(fusion);
  EXPECT_EQ(after.at(40, 50), kFreeValue);
  EXPECT_EQ(after.at(20, 60), kOccupiedValue);
}

// Without a second participant to corroborate it, the robot that came later is the one weighed
// against what was there first, as before: first evidence wins between two lone robots.
TEST(QuarantineTest, BetweenTwoLoneRobotsTheFirstEvidenceStillWins) {
  TileFusion fusion = MakeFusion();
  fusion.SetRobotSource(RobotId{"lost"}, "participant-l");
  fusion.SetRobotSource(RobotId{"alpha"}, "participant-a");
  Feed(&fusion, "lost", PhantomShelves(), kT0);
  Fuse(&fusion);
  Feed(&fusion, "alpha", Room(), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"alpha"}).standing, Standing::kQuarantined);
  EXPECT_EQ(Fused(fusion).at(40, 50), kOccupiedValue);
}

TEST(QuarantineTest, AnAdmittedRobotIsFusedAndStaysSo) {
  TileFusion fusion = MakeFusion();
  Establish(&fusion, /*shelves=*/true);
  Feed(&fusion, "beta", Room(), kT0 + std::chrono::seconds(10));
  Fuse(&fusion);
  ASSERT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kQuarantined);
  fusion.TakeTrustChanges();
  EXPECT_TRUE(fusion.AdmitRobot(RobotId{"beta"}));
  Fuse(&fusion);
  EXPECT_EQ(fusion.TrustOf(RobotId{"beta"}).standing, Standing::kAdmitted);
  EXPECT_NE(Fused(fusion).at(40, 50), kOccupiedValue);  // the shelves are gone
  ASSERT_EQ(fusion.TakeTrustChanges().size(), 1u);
}

TEST(QuarantineTest, ARestoredFusionQuarantinesTheSameRobotWhateverTheOrder) {
  TileFusion live = MakeFusion();
  Establish(&live);
  Feed(&live, "mallory", Room(40, 0), kT0 + std::chrono::seconds(10));
  Fuse(&live);
  ASSERT_EQ(live.TrustOf(RobotId{"mallory"}).standing, Standing::kQuarantined);
  std::vector<std::pair<RobotId, TileId>> contributions = live.contributions();
  std::reverse(contributions.begin(), contributions.end());  // mallory's first
  TileFusion restored = MakeFusion();
  for (const auto& [robot, tile] : contributions) {
    ASSERT_TRUE(
        restored.ImportContribution(robot, tile, *live.ExportContribution(robot, tile)).ok());
  }
  Fuse(&restored);
  EXPECT_EQ(restored.TrustOf(RobotId{"mallory"}).standing, Standing::kQuarantined);
  EXPECT_EQ(restored.TrustOf(RobotId{"alpha"}).standing, Standing::kTrusted);
  EXPECT_EQ(Fused(restored).data(), Fused(live).data());
}

}  // namespace
}  // namespace fleetmap::fusion
