#include "bench/register/map_pair_generator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "common/grid/map_io.hpp"

namespace fleetmap::bench {
namespace {

grid::OccupancyGrid House() {
  const std::string path = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";
  StatusOr<grid::LoadedMap> loaded = grid::LoadMap(path);
  EXPECT_TRUE(loaded.ok()) << loaded.status();
  return loaded.ok() ? loaded->grid : grid::OccupancyGrid();
}

struct Agreement {
  double same_state = 0.0;  // share of B's known cells whose source cell has B's state
  double known_in_a = 0.0;  // share of B's known cells that land on A's known cells
};

// Where the truth puts B's known cells: the source map's cell and A's cell under each.
Agreement Check(const MapPair& pair, const grid::OccupancyGrid& source) {
  int known = 0, same = 0, in_a = 0;
  for (int y = 0; y < pair.b.height(); ++y) {
    for (int x = 0; x < pair.b.width(); ++x) {
      const grid::CellState state = pair.b.StateAt(x, y);
      if (state == grid::CellState::kUnknown) continue;
      ++known;
      const Point2 p = pair.a_from_b * pair.b.CellCenter(x, y);
      if (const auto s = source.CellAt(p); s && source.StateAt(s->x, s->y) == state) ++same;
      if (const auto a = pair.a.CellAt(p);
          a && pair.a.StateAt(a->x, a->y) != grid::CellState::kUnknown) {
        ++in_a;
      }
    }
  }
  return {static_cast<double>(same) / known, static_cast<double>(in_a) / known};
}

TEST(MapPairGeneratorTest, ReachesTheRequestedOverlapAndKeepsTheTruth) {
  const grid::OccupancyGrid house = House();
  ASSERT_FALSE(house.empty());
  const MapPairOptions options;
  for (const double target : {0.2, 0.5, 0.7}) {
    SCOPED_TRACE(target);
    std::mt19937 rng(7);
    StatusOr<MapPair> pair = MakeMapPair(house, target, options, rng);
    for (int retry = 0; retry < 4 && !pair.ok(); ++retry) {
      pair = MakeMapPair(house, target, options, rng);
    }
    ASSERT_TRUE(pair.ok()) << pair.status();
    EXPECT_NEAR(pair->overlap, target, options.overlap_tolerance + 1e-9);
    // B lives in a frame of its own, far from A's.
    EXPECT_GT((pair->b.origin().translation() - pair->a.origin().translation()).norm(), 1.0);
    const Agreement agreement = Check(*pair, house);
    // Nearest-neighbour resampling and the specks move a few cells; the rest must match.
    EXPECT_GT(agreement.same_state, 0.95);
    EXPECT_NEAR(agreement.known_in_a, pair->overlap, 0.05);
  }
}

// Wall noise moves wall faces of A and B apart, by a cell: two SLAM runs of one wall, not two
// crops of one map. Noise off draws nothing more, so the pairs of a seed are unchanged.
TEST(MapPairGeneratorTest, WallNoiseMovesFacesOfEachMapApartByACell) {
  const grid::OccupancyGrid house = House();
  ASSERT_FALSE(house.empty());
  const auto make = [&house](double noise) {
    MapPairOptions options;
    options.wall_noise = noise;
    options.min_specks = options.max_specks = 0;
    std::mt19937 rng(11);
    StatusOr<MapPair> pair = MakeMapPair(house, 0.5, options, rng);
    for (int retry = 0; retry < 4 && !pair.ok(); ++retry) {
      pair = MakeMapPair(house, 0.5, options, rng);
    }
    EXPECT_TRUE(pair.ok()) << pair.status();
    return pair.ok() ? *pair : MapPair{};
  };
  const MapPair clean = make(0.0);
  const MapPair noisy = make(0.3);
  ASSERT_FALSE(clean.a.empty());
  ASSERT_EQ(noisy.a.width(), clean.a.width());  // the same crop: noise comes after it
  ASSERT_EQ(noisy.a.height(), clean.a.height());
  int moved = 0, far_moves = 0, occupied = 0;
  for (int y = 0; y < clean.a.height(); ++y) {
    for (int x = 0; x < clean.a.width(); ++x) {
      const grid::CellState was = clean.a.StateAt(x, y), is = noisy.a.StateAt(x, y);
      occupied += was == grid::CellState::kOccupied;
      if (was == is) continue;
      ++moved;
      EXPECT_NE(is, grid::CellState::kUnknown);  // only free and occupied trade places
      // A moved cell lies on a face: a cell of the other state beside it.
      bool on_face = false;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        on_face = on_face || (clean.a.Contains(x + dx, y + dy) &&
                              clean.a.StateAt(x + dx, y + dy) != grid::CellState::kUnknown &&
                              clean.a.StateAt(x + dx, y + dy) != was);
      }
      far_moves += !on_face;
    }
  }
  EXPECT_GT(moved, occupied / 20);  // about 0.3 of the face cells move
  EXPECT_LT(moved, occupied);
  EXPECT_EQ(far_moves, 0);
  const grid::StateCounts b_clean = clean.b.CountStates(), b_noisy = noisy.b.CountStates();
  EXPECT_NE(b_noisy.occupied, b_clean.occupied);  // B's walls moved too, on their own draws
}

TEST(MapPairGeneratorTest, CropsAreExplorationLikeNotRectangles) {
  const grid::OccupancyGrid house = House();
  ASSERT_FALSE(house.empty());
  std::mt19937 rng(3);
  StatusOr<MapPair> pair = MakeMapPair(house, 0.5, {}, rng);
  for (int retry = 0; retry < 4 && !pair.ok(); ++retry) pair = MakeMapPair(house, 0.5, {}, rng);
  ASSERT_TRUE(pair.ok()) << pair.status();
  // A holds part of the house's known cells, not all of them, and much of its box is unknown.
  const grid::StateCounts a = pair->a.CountStates();
  const grid::StateCounts all = house.CountStates();
  const double share = static_cast<double>(a.free + a.occupied) / (all.free + all.occupied);
  EXPECT_GT(share, 0.25);
  EXPECT_LT(share, 0.85);
  EXPECT_GT(a.unknown, 0);
}

TEST(MapPairGeneratorTest, GrowsBInItsOwnFrameAsTheRobotDrove) {
  const grid::OccupancyGrid house = House();
  ASSERT_FALSE(house.empty());
  MapPairOptions options;
  options.growth_steps = 4;
  std::mt19937 rng(5);
  StatusOr<MapPair> pair = MakeMapPair(house, 0.5, options, rng);
  for (int retry = 0; retry < 4 && !pair.ok(); ++retry)
    pair = MakeMapPair(house, 0.5, options, rng);
  ASSERT_TRUE(pair.ok()) << pair.status();
  ASSERT_EQ(pair->b_growing.size(), 3u);
  int64_t previous = 0;
  for (const grid::OccupancyGrid& step : pair->b_growing) {
    // B's grid and frame, fewer known cells, each of them B's own (B's frame: the same truth).
    ASSERT_EQ(step.width(), pair->b.width());
    ASSERT_EQ(step.height(), pair->b.height());
    EXPECT_EQ(step.origin().translation(), pair->b.origin().translation());
    const grid::StateCounts counts = step.CountStates();
    const int64_t known = counts.free + counts.occupied;
    EXPECT_GT(known, previous);
    previous = known;
    for (int y = 0; y < step.height(); ++y) {
      for (int x = 0; x < step.width(); ++x) {
        if (step.at(x, y) != grid::kUnknownValue) {
          ASSERT_EQ(step.at(x, y), pair->b.at(x, y));
        }
      }
    }
  }
  const grid::StateCounts full = pair->b.CountStates();
  EXPECT_LT(previous, full.free + full.occupied);
  // Without growth_steps the same draw makes the same pair, and no steps.
  std::mt19937 again(5);
  StatusOr<MapPair> plain = MakeMapPair(house, 0.5, {}, again);
  for (int retry = 0; retry < 4 && !plain.ok(); ++retry) plain = MakeMapPair(house, 0.5, {}, again);
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->b_growing.empty());
  EXPECT_EQ(plain->b.data(), pair->b.data());
}

TEST(MapPairGeneratorTest, TurnsIntoANewFrameByAQuarterExactly) {
  grid::OccupancyGrid map(4, 2, 0.5, Pose2{1.0, 2.0, 0.0});
  map.at(0, 0) = grid::kOccupiedValue;
  map.at(3, 1) = grid::kFreeValue;
  Transform2 map_from_turned;
  const grid::OccupancyGrid turned =
      TurnIntoNewFrame(map, std::numbers::pi / 2, Pose2{-100.0, 50.0, 0.3}, &map_from_turned);
  int checked = 0;
  for (int y = 0; y < turned.height(); ++y) {
    for (int x = 0; x < turned.width(); ++x) {
      if (turned.at(x, y) == grid::kUnknownValue) continue;
      const auto cell = map.CellAt(map_from_turned * turned.CellCenter(x, y));
      ASSERT_TRUE(cell.has_value());
      EXPECT_EQ(map.at(cell->x, cell->y), turned.at(x, y));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);
}

// Drift: the pivot stays, a pillar 2.5 m away along x moves by the scale (8 % -> 20 cm), and
// the bend turns a pillar ahead of the pivot sideways; the map frame is kept.
TEST(MapPairGeneratorTest, WarpsAboutThePivot) {
  grid::OccupancyGrid map(200, 200, 0.05, Pose2{3.0, -2.0, 0.0});
  for (int d = -1; d <= 1; ++d) {  // 3 x 3 pillars: at the pivot's cell and 2.5 m along x
    for (int e = -1; e <= 1; ++e) {
      map.at(100 + d, 100 + e) = grid::kOccupiedValue;
      map.at(150 + d, 100 + e) = grid::kOccupiedValue;
    }
  }
  const Point2 pivot = map.CellCenter(100, 100);
  const auto occupied_near = [](const grid::OccupancyGrid& g, const Point2& p) {
    for (int y = 0; y < g.height(); ++y) {
      for (int x = 0; x < g.width(); ++x) {
        if (g.StateAt(x, y) == grid::CellState::kOccupied &&
            (g.CellCenter(x, y) - p).norm() <= 0.051) {
          return true;
        }
      }
    }
    return false;
  };
  const grid::OccupancyGrid scaled = Warp(map, pivot, 0.08, 0.0);
  EXPECT_TRUE(occupied_near(scaled, pivot));
  EXPECT_TRUE(occupied_near(scaled, pivot + Point2(2.7, 0.0)));
  EXPECT_FALSE(occupied_near(scaled, pivot + Point2(2.5, 0.0)));
  // Bent by 2 degrees per metre: 2.5 m ahead turns by 5 degrees, about 22 cm sideways.
  const double bend = 2.0 * std::numbers::pi / 180.0;
  const grid::OccupancyGrid bent = Warp(map, pivot, 0.0, bend);
  const double turn = bend * 2.5;
  EXPECT_TRUE(occupied_near(bent, pivot + 2.5 * Point2(std::cos(turn), std::sin(turn))));
  EXPECT_FALSE(occupied_near(bent, pivot + Point2(2.5, 0.0)));
}

TEST(MapPairGeneratorTest, RefusesAMapWithoutFreeSpace) {
  std::mt19937 rng(1);
  const grid::OccupancyGrid walls(50, 50, 0.05, Pose2{}, grid::kOccupiedValue);
  const StatusOr<MapPair> pair = MakeMapPair(walls, 0.5, {}, rng);
  ASSERT_FALSE(pair.ok());
  EXPECT_THAT(pair.status().message(), ::testing::HasSubstr("free cells"));
}

}  // namespace
}  // namespace fleetmap::bench
