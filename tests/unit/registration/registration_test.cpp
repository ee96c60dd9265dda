#include "common/registration/registration.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "bench/register/map_pair_generator.hpp"
#include "common/grid/map_io.hpp"

namespace fleetmap::registration {

// gtest prints a Registration with this (found by ADL).
void PrintTo(const Registration& r, std::ostream* os) {
  *os << (r.found ? "found " : "not found ") << r.a_from_b << " confidence " << r.confidence
      << " overlap " << r.overlap;
}

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

void Fill(grid::OccupancyGrid& g, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (g.Contains(x, y)) g.at(x, y) = value;
    }
  }
}

// A room wall: a free interior bounded by a one-cell occupied ring.
void Room(grid::OccupancyGrid& g, int x0, int y0, int x1, int y1) {
  Fill(g, x0, y0, x1, y1, grid::kOccupiedValue);
  Fill(g, x0 + 1, y0 + 1, x1 - 1, y1 - 1, grid::kFreeValue);
}

// Rooms of different sizes, doors, a pillar and an L-shaped shelf: nothing repeats.
grid::OccupancyGrid Floor() {
  grid::OccupancyGrid g(220, 160, 0.05);
  Room(g, 5, 5, 214, 154);
  Fill(g, 80, 5, 80, 100, grid::kOccupiedValue);
  Fill(g, 80, 40, 80, 52, grid::kFreeValue);  // door
  Fill(g, 80, 100, 160, 100, grid::kOccupiedValue);
  Fill(g, 120, 100, 131, 100, grid::kFreeValue);    // door
  Fill(g, 30, 110, 37, 117, grid::kOccupiedValue);  // pillar
  Fill(g, 150, 20, 195, 22, grid::kOccupiedValue);  // shelf
  Fill(g, 193, 22, 195, 70, grid::kOccupiedValue);
  Fill(g, 40, 30, 43, 33, grid::kOccupiedValue);  // box
  Fill(g, 170, 130, 172, 150, grid::kOccupiedValue);
  return g;
}

// Crops and turned copies as the registration benchmark makes them (bench/register).
grid::OccupancyGrid Crop(const grid::OccupancyGrid& g, int x0, int y0, int w, int h) {
  return bench::CropCells(g, x0, y0, w, h);
}

grid::OccupancyGrid Turn(const grid::OccupancyGrid& crop, double yaw, const Pose2& origin,
                         Transform2* orig_from_b) {
  return bench::TurnIntoNewFrame(crop, yaw, origin, orig_from_b);
}

// Translation error at the centroid of B's known cells (metres) and yaw error (radians).
struct PoseError {
  double translation;
  double yaw;
};

PoseError ErrorOf(const grid::OccupancyGrid& b, const Pose2& estimate, const Transform2& truth) {
  const Point2 centroid = bench::KnownCentroid(b);
  const Point2 d = estimate.ToTransform() * centroid - truth * centroid;
  return {d.norm(), std::abs(NormalizeAngle(estimate.yaw - Pose2::FromTransform(truth).yaw))};
}

MATCHER_P2(IsNearTruth, b, truth, "places B within 3 cells and 2 degrees of the truth") {
  const PoseError e = ErrorOf(b, arg.a_from_b, truth);
  *result_listener << "estimate " << arg.a_from_b << ", truth " << Pose2::FromTransform(truth)
                   << ", error " << e.translation << " m, " << e.yaw / kDegree
                   << " deg, confidence " << arg.confidence << ", why not: " << arg.why_not;
  return arg.found && e.translation <= 3.0 * b.resolution() + 1e-9 && e.yaw <= 2.0 * kDegree;
}

TEST(RegistrationTest, RecoversKnownTransformsOnASyntheticFloorInAllQuadrants) {
  const grid::OccupancyGrid floor = Floor();
  const grid::OccupancyGrid a = Crop(floor, 0, 0, 150, 160);
  const grid::OccupancyGrid crop_b = Crop(floor, 70, 0, 150, 160);
  for (const double yaw_deg : {12.0, 97.0, 185.0, -73.0}) {
    SCOPED_TRACE(yaw_deg);
    Transform2 truth;
    const grid::OccupancyGrid b =
        Turn(crop_b, yaw_deg * kDegree, Pose2{-31.5, 148.25, 0.4}, &truth);
    const StatusOr<Registration> r = Register(a, b, {});
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_THAT(*r, IsNearTruth(b, truth));
    EXPECT_GT(r->confidence, 0.0);
    EXPECT_GT(r->overlap, 0.3);
  }
}

TEST(RegistrationTest, RefusesALongStraightCorridor) {
  grid::OccupancyGrid corridor(400, 40, 0.05);
  Fill(corridor, 0, 10, 399, 10, grid::kOccupiedValue);
  Fill(corridor, 0, 11, 399, 28, grid::kFreeValue);
  Fill(corridor, 0, 29, 399, 29, grid::kOccupiedValue);
  const grid::OccupancyGrid a = Crop(corridor, 0, 0, 250, 40);
  const grid::OccupancyGrid b = Crop(corridor, 150, 0, 250, 40);
  const StatusOr<Registration> r = Register(a, b, {});
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_FALSE(r->found) << r->a_from_b;
  EXPECT_THAT(r->why_not, ::testing::Not(::testing::IsEmpty()));
}

TEST(RegistrationTest, RefusesTwoIdenticalRoomsSideBySide) {
  grid::OccupancyGrid a(200, 80, 0.05);
  Room(a, 0, 0, 99, 79);
  Room(a, 100, 0, 199, 79);
  Fill(a, 20, 20, 25, 25, grid::kOccupiedValue);
  Fill(a, 120, 20, 125, 25, grid::kOccupiedValue);
  grid::OccupancyGrid b = Crop(a, 100, 0, 100, 80);  // one of the two rooms
  const StatusOr<Registration> r = Register(a, b, {});
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_FALSE(r->found) << r->a_from_b;
}

// tb3_world's case: an arena that is the same turned by 180 degrees about its centre, so a crop
// of it fits both where it was cut and at the mirror place; both verify alike.
grid::OccupancyGrid PointSymmetricArena() {
  grid::OccupancyGrid arena(200, 120, 0.05);
  Room(arena, 0, 0, 199, 119);
  const auto fill_twice = [&arena](int x0, int y0, int x1, int y1) {
    Fill(arena, x0, y0, x1, y1, grid::kOccupiedValue);
    Fill(arena, 199 - x1, 119 - y1, 199 - x0, 119 - y0, grid::kOccupiedValue);
  };
  fill_twice(30, 20, 37, 27);  // box
  fill_twice(60, 70, 90, 72);  // shelf
  fill_twice(88, 72, 90, 100);
  fill_twice(20, 90, 22, 110);  // a short wall
  return arena;
}

TEST(RegistrationTest, RefusesACropOfAPointSymmetricArena) {
  const grid::OccupancyGrid arena = PointSymmetricArena();
  Transform2 truth;
  const grid::OccupancyGrid b =
      Turn(Crop(arena, 0, 0, 130, 120), 33.0 * kDegree, Pose2{12.0, -4.0, 0.2}, &truth);
  const StatusOr<Registration> r = Register(arena, b, {});
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_FALSE(r->found) << r->a_from_b;
  EXPECT_THAT(r->why_not, ::testing::HasSubstr("ambiguous"));
  // Nothing tells the two apart: the refusal says how little does.
  EXPECT_THAT(r->why_not, ::testing::HasSubstr("where the two disagree, 0 m of walls favour"));
}

// The same arena with one pillar the turned copy does not have (a warehouse's racks repeat under
// a half turn, its pallets do not): the cells where the two placements disagree tell them apart.
TEST(RegistrationTest, PlacesACropOfASymmetricArenaByWhatBreaksTheSymmetry) {
  grid::OccupancyGrid arena = PointSymmetricArena();
  Fill(arena, 50, 45, 57, 52, grid::kOccupiedValue);  // a 0.4 m pillar, once
  Transform2 truth;
  const grid::OccupancyGrid b =
      Turn(Crop(arena, 0, 0, 130, 120), 33.0 * kDegree, Pose2{12.0, -4.0, 0.2}, &truth);
  const StatusOr<Registration> r = Register(arena, b, {});
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_THAT(*r, IsNearTruth(b, truth));
  // Without the test on the disagreeing cells the half turn is still a twin.
  RegistrationOptions never_told_apart;
  never_told_apart.symmetry_telling_m = 0.0;
  const StatusOr<Registration> refused = Register(arena, b, never_told_apart);
  ASSERT_TRUE(refused.ok()) << refused.status();
  EXPECT_FALSE(refused->found) << refused->a_from_b;
  EXPECT_THAT(refused->why_not, ::testing::HasSubstr("ambiguous"));
}

TEST(RegistrationTest, RefusesMapsThatDoNotOverlap) {
  const grid::OccupancyGrid floor = Floor();
  const grid::OccupancyGrid a = Crop(floor, 0, 0, 90, 160);
  const grid::OccupancyGrid b = Crop(floor, 130, 0, 90, 160);
  const StatusOr<Registration> r = Register(a, b, {});
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_FALSE(r->found) << r->a_from_b << " " << r->confidence;
}

TEST(RegistrationTest, RefusesBadInputWithAClearMessage) {
  const grid::OccupancyGrid floor = Floor();
  const grid::OccupancyGrid coarse(50, 50, 0.1, Pose2{}, grid::kOccupiedValue);
  StatusOr<Registration> r = Register(floor, coarse, {});
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), ::testing::HasSubstr("resolution"));
  EXPECT_THAT(r.status().message(), ::testing::HasSubstr("resample"));

  r = Register(floor, grid::OccupancyGrid(), {});
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), ::testing::HasSubstr("map B is empty"));

  const grid::OccupancyGrid unknown(50, 50, 0.05);
  r = Register(unknown, floor, {});
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), ::testing::HasSubstr("map A has no occupied cell"));

  grid::OccupancyGrid nan_origin = floor;
  nan_origin = grid::OccupancyGrid(floor.width(), floor.height(), floor.resolution(),
                                   Pose2{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0});
  r = Register(floor, nan_origin, {});
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), ::testing::HasSubstr("non-finite origin"));

  RegistrationOptions bad;
  bad.max_peak_ratio = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(bad.Validate().ok());
  r = Register(floor, floor, bad);
  EXPECT_FALSE(r.ok());
}

// Issue 33: a map whose resolution crossed a float32 field (a DDS message, a .vmap) registers on
// the map it came from; a different resolution is refused with both printed cleanly.
TEST(RegistrationTest, ComparesResolutionsWithARelativeTolerance) {
  const grid::OccupancyGrid floor = Floor();
  ASSERT_EQ(floor.resolution(), 0.05);
  grid::OccupancyGrid widened(floor.width(), floor.height(), static_cast<double>(0.05F),
                              floor.origin());
  widened.mutable_data() = floor.data();
  const StatusOr<Registration> same = Register(floor, widened, {});
  ASSERT_TRUE(same.ok()) << same.status();
  EXPECT_TRUE(same->found);

  const grid::OccupancyGrid coarse(50, 50, 0.1, Pose2{}, grid::kOccupiedValue);
  const StatusOr<Registration> different = Register(floor, coarse, {});
  ASSERT_FALSE(different.ok());
  EXPECT_THAT(different.status().message(),
              ::testing::HasSubstr("map A's resolution 0.05 m differs from map B's 0.1 m"));
}

// found is the placement decision: a verified placement below the placement bar is refused,
// with the confidence and the bar in why_not, and its best guess kept.
TEST(RegistrationTest, FoundOnlyAtThePlacementBar) {
  const grid::OccupancyGrid floor = Floor();
  const grid::OccupancyGrid a = Crop(floor, 0, 0, 150, 160);
  Transform2 truth;
  const grid::OccupancyGrid b =
      Turn(Crop(floor, 70, 0, 150, 160), 12.0 * kDegree, Pose2{-31.5, 148.25, 0.4}, &truth);
  RegistrationOptions options;
  EXPECT_EQ(options.min_confidence, kPlacementConfidence);
  options.min_confidence = 0.0;
  const StatusOr<Registration> open = Register(a, b, options);
  ASSERT_TRUE(open.ok()) << open.status();
  ASSERT_THAT(*open, IsNearTruth(b, truth));
  ASSERT_LT(open->confidence, 1.0);

  options.min_confidence = std::min(1.0, open->confidence + 0.001);
  const StatusOr<Registration> barred = Register(a, b, options);
  ASSERT_TRUE(barred.ok()) << barred.status();
  EXPECT_FALSE(barred->found);
  EXPECT_THAT(barred->why_not, ::testing::HasSubstr("below the placement bar"));
  EXPECT_EQ(barred->confidence, open->confidence);
  const PoseError guess = ErrorOf(b, barred->a_from_b, truth);  // the best guess is kept
  EXPECT_LE(guess.translation, 3.0 * b.resolution() + 1e-9);
  EXPECT_LE(guess.yaw, 2.0 * kDegree);
  // A bar that two decimals would round (0.999 to "1.00") is quoted as it is.
  options.min_confidence = 0.999;
  const StatusOr<Registration> high_bar = Register(a, b, options);
  ASSERT_TRUE(high_bar.ok()) << high_bar.status();
  EXPECT_FALSE(high_bar->found);  // no calibration claims 0.999
  EXPECT_THAT(high_bar->why_not, ::testing::HasSubstr("below the placement bar 0.9990"));

  options.min_confidence = 1.5;
  EXPECT_FALSE(options.Validate().ok());
  EXPECT_FALSE(Register(a, b, options).ok());
}

TEST(RegistrationTest, DescribesItsOptions) {
  const std::string text = DescribeOptions(RegistrationOptions{});
  EXPECT_THAT(text, ::testing::HasSubstr("min_confidence: 0.95"));
  EXPECT_THAT(text, ::testing::HasSubstr("max_peak_ratio: 0.85"));
  EXPECT_THAT(text, ::testing::HasSubstr("thresholds:\n  occupied: 0.65"));
}

// The real maps of ../shared/data/maps that are present.
std::vector<std::pair<std::string, grid::OccupancyGrid>> RealMaps() {
  std::vector<std::pair<std::string, grid::OccupancyGrid>> maps;
  for (const char* name : {"intel_lab", "aces3_austin", "nav2_warehouse", "willow_garage_2010",
                           "strands_kth", "aws_small_house", "tb3_world"}) {
    auto loaded = grid::LoadMap(std::string(FLEETMAP_SHARED_MAPS_DIR) + "/" + name + ".yaml");
    if (loaded.ok()) maps.emplace_back(name, std::move(loaded->grid));
  }
  return maps;
}

// The bounding box of a map's known cells.
struct Box {
  int x0, y0, x1, y1;
};

Box KnownBox(const grid::OccupancyGrid& g) {
  Box box{g.width(), g.height(), -1, -1};
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (g.at(x, y) == grid::kUnknownValue) continue;
      box.x0 = std::min(box.x0, x);
      box.y0 = std::min(box.y0, y);
      box.x1 = std::max(box.x1, x);
      box.y1 = std::max(box.y1, y);
    }
  }
  return box;
}

TEST(RegistrationTest, RecoversKnownTransformsOnCropsOfRealMaps) {
  const auto maps = RealMaps();
  ASSERT_FALSE(maps.empty()) << "no real map in " << FLEETMAP_SHARED_MAPS_DIR;
  int cases = 0;
  int placed = 0;
  std::vector<double> times_ms;
  for (const auto& [name, map] : maps) {
    // tb3_world's arena is point-symmetric: turned by 180 degrees, crop B covers crop A exactly,
    // so that pair has two equally good answers and is no test of recovery.
    if (name == "tb3_world") continue;
    const Box box = KnownBox(map);
    const int w = box.x1 - box.x0 + 1, h = box.y1 - box.y0 + 1;
    // Two crops across the longer side, each 5/8 of it: they share 60 % of a crop.
    const bool along_x = w >= h;
    const int crop_len = (along_x ? w : h) * 5 / 8;
    const int shift = (along_x ? w : h) - crop_len;
    const grid::OccupancyGrid a =
        along_x ? Crop(map, box.x0, box.y0, crop_len, h) : Crop(map, box.x0, box.y0, w, crop_len);
    const grid::OccupancyGrid crop_b = along_x ? Crop(map, box.x0 + shift, box.y0, crop_len, h)
                                               : Crop(map, box.x0, box.y0 + shift, w, crop_len);
    int quadrant = 0;
    for (const double yaw_deg : {23.0, 118.0, -157.0, -64.0}) {
      SCOPED_TRACE(name + " yaw " + std::to_string(yaw_deg));
      Transform2 truth;
      const Pose2 origin{-250.0 + 117.3 * quadrant, 480.0 - 91.7 * quadrant, 1.3 - quadrant};
      const grid::OccupancyGrid b = Turn(crop_b, yaw_deg * kDegree, origin, &truth);
      const auto start = std::chrono::steady_clock::now();
      const StatusOr<Registration> r = Register(a, b, {});
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      ASSERT_TRUE(r.ok()) << r.status();
      EXPECT_THAT(*r, IsNearTruth(b, truth));
      placed += ::testing::Matches(IsNearTruth(b, truth))(*r) ? 1 : 0;
      times_ms.push_back(ms);
      ++quadrant;
      ++cases;
    }
  }
  EXPECT_GT(cases, 0);
  // For docs/registration.md (printed, not asserted: a test asserts no wall-clock time).
  std::sort(times_ms.begin(), times_ms.end());
  if (!times_ms.empty()) {
    std::cout << "real-map crops: " << placed << " of " << cases
              << " placed within 3 cells and 2 deg; median " << times_ms[times_ms.size() / 2]
              << " ms, slowest " << times_ms.back() << " ms per pair\n";
  }
}

// Drift (issue 31): crop B of each real map bent and stretched as a second SLAM run would map
// the same walls (2 % scale, 0.1 degree per metre of heading creep, about B's known centroid).
// A drifted map has no rigid truth, so a placement is judged where B overlaps A (as `bench
// register` judges drifted pairs): within 3 cells and 2 degrees there. A rigid verification sees
// B's far walls miss A's and refuses the right placements; the drift-tolerant one, where each
// block of B may move by what drift could have done there, places more, and nothing wrongly.
TEST(RegistrationTest, PlacesDriftedCropsOfRealMapsThatARigidVerificationRefuses) {
  const auto maps = RealMaps();
  ASSERT_FALSE(maps.empty()) << "no real map in " << FLEETMAP_SHARED_MAPS_DIR;
  RegistrationOptions rigid;
  rigid.max_drift_per_m = 0.0;
  const RegistrationOptions drift_tolerant;  // the default, 3 cm per metre
  ASSERT_EQ(drift_tolerant.max_drift_per_m, 0.03);
  constexpr double kBend = 0.1 * kDegree;
  int cases = 0, placed_rigid = 0, placed_with_drift = 0, wrong = 0;
  for (const auto& [name, map] : maps) {
    if (name == "tb3_world") continue;  // point-symmetric: see the test above
    const Box box = KnownBox(map);
    const int w = box.x1 - box.x0 + 1, h = box.y1 - box.y0 + 1;
    const bool along_x = w >= h;
    const int crop_len = (along_x ? w : h) * 5 / 8;
    const int shift = (along_x ? w : h) - crop_len;
    bench::MapPair crops;  // both crops in the source map's frame: the truth is the identity
    crops.a =
        along_x ? Crop(map, box.x0, box.y0, crop_len, h) : Crop(map, box.x0, box.y0, w, crop_len);
    crops.b = along_x ? Crop(map, box.x0 + shift, box.y0, crop_len, h)
                      : Crop(map, box.x0, box.y0 + shift, w, crop_len);
    const Point2 pivot = bench::KnownCentroid(crops.b);
    const Point2 overlap = bench::OverlapCentroid(crops);
    for (const double scale : {0.02, -0.02}) {
      SCOPED_TRACE(name + " scale " + std::to_string(scale));
      const bench::WarpedPoint judged = bench::WarpPoint(crops.b, pivot, scale, kBend, overlap);
      Transform2 crop_from_b;
      const grid::OccupancyGrid b = Turn(bench::Warp(crops.b, pivot, scale, kBend), 71.0 * kDegree,
                                         Pose2{35.0, -140.0, -0.6}, &crop_from_b);
      const Point2 judged_in_b = crop_from_b.inverse() * judged.point;
      const double truth_yaw = Pose2::FromTransform(crop_from_b).yaw - judged.turn;
      const auto right = [&](const Registration& r) {
        const double error = (r.a_from_b.ToTransform() * judged_in_b - overlap).norm();
        return error <= 3.0 * b.resolution() &&
               std::abs(NormalizeAngle(r.a_from_b.yaw - truth_yaw)) <= 2.0 * kDegree;
      };
      const StatusOr<Registration> with_drift = Register(crops.a, b, drift_tolerant);
      const StatusOr<Registration> without = Register(crops.a, b, rigid);
      ASSERT_TRUE(with_drift.ok() && without.ok());
      EXPECT_FALSE(with_drift->found && !right(*with_drift))
          << ::testing::PrintToString(*with_drift) << ", drift " << with_drift->drift;
      placed_with_drift += with_drift->found && right(*with_drift) ? 1 : 0;
      wrong += with_drift->found && !right(*with_drift) ? 1 : 0;
      placed_rigid += without->found && right(*without) ? 1 : 0;
      EXPECT_EQ(without->drift, 0.0);
      ++cases;
    }
  }
  std::cout << "drifted real-map crops: " << placed_with_drift << " of " << cases
            << " placed (rigid verification: " << placed_rigid << "), " << wrong << " wrong\n";
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(placed_with_drift, placed_rigid);
}

TEST(RegistrationTest, RecoversATurnBetweenMapsOf2000By2000Cells) {
  const auto maps = RealMaps();
  ASSERT_FALSE(maps.empty()) << "no real map in " << FLEETMAP_SHARED_MAPS_DIR;
  const grid::OccupancyGrid* largest = &maps.front().second;
  for (const auto& [name, map] : maps) {
    if (map.cell_count() > largest->cell_count() && name != "tb3_world") largest = &map;
  }
  // The largest map, upsampled by the largest integer factor that fits, in a 2000 x 2000 grid.
  constexpr int kSide = 2000;
  const int factor = std::max(1, kSide / std::max(largest->width(), largest->height()));
  grid::OccupancyGrid a(kSide, kSide, largest->resolution() / factor, Pose2{-7.0, 3.0, 0.0});
  for (int y = 0; y < largest->height() * factor && y < kSide; ++y) {
    for (int x = 0; x < largest->width() * factor && x < kSide; ++x) {
      a.at(x, y) = largest->at(x / factor, y / factor);
    }
  }
  // B holds A's cells turned by 90 degrees: b(x, y) = a(kSide - 1 - y, x).
  grid::OccupancyGrid b(kSide, kSide, a.resolution(), Pose2{120.0, -45.0, 0.7});
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) b.at(x, y) = a.at(kSide - 1 - y, x);
  }
  Transform2 grid_a_from_grid_b = Transform2::Identity();
  grid_a_from_grid_b.translate(Point2(kSide * a.resolution(), 0.0));
  grid_a_from_grid_b.rotate(std::numbers::pi / 2);
  const Transform2 truth =
      a.origin().ToTransform() * grid_a_from_grid_b * b.origin().ToTransform().inverse();
  const auto start = std::chrono::steady_clock::now();
  const StatusOr<Registration> r = Register(a, b, {});
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_THAT(*r, IsNearTruth(b, truth));
  std::cout << "2000 x 2000 cells: " << ms << " ms\n";  // printed, not asserted
}

}  // namespace
}  // namespace fleetmap::registration
