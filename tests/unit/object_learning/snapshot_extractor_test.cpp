#include "common/object_learning/snapshot_extractor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/object_learning/object_learner.hpp"

namespace fleetmap::object_learning {
namespace {

using ::testing::HasSubstr;

// A 6 x 6 m room: free inside, walls on the border, 5 cm cells.
grid::OccupancyGrid Room() {
  grid::OccupancyGrid map(120, 120, 0.05, Pose2{}, grid::kFreeValue);
  for (int i = 0; i < 120; ++i) {
    map.at(i, 0) = map.at(i, 119) = map.at(0, i) = map.at(119, i) = grid::kOccupiedValue;
  }
  return map;
}

// A box outline (as a laser sees it) with its inside unknown.
void AddBox(grid::OccupancyGrid* map, int x0, int y0, int w, int h) {
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) {
      const bool edge = x == x0 || y == y0 || x == x0 + w - 1 || y == y0 + h - 1;
      map->at(x, y) = edge ? grid::kOccupiedValue : grid::kUnknownValue;
    }
  }
}

TEST(SnapshotExtractorTest, FindsExactlyTheMovedObjects) {
  grid::OccupancyGrid a = Room(), b = Room();
  AddBox(&a, 20, 20, 12, 8);  // moved: here in a...
  AddBox(&b, 70, 70, 12, 8);  // ...there in b
  AddBox(&a, 40, 80, 8, 8);   // static: in both
  AddBox(&b, 40, 80, 8, 8);
  // Border artifact: b sees the west wall one cell further in; a speckle in a.
  for (int y = 10; y < 110; ++y) b.at(1, y) = grid::kOccupiedValue;
  a.at(90, 30) = grid::kOccupiedValue;
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, b}, SnapshotOptions{});
  ASSERT_TRUE(set.ok()) << set.status();
  ASSERT_EQ(set->snapshots.size(), 2u);
  EXPECT_EQ(set->per_map, (std::vector<int>{1, 1}));
  EXPECT_EQ(set->snapshots[0].map_index, 0);
  EXPECT_NEAR(set->snapshots[0].centre.x(), 25.5 * 0.05, 0.06);
  EXPECT_NEAR(set->snapshots[0].centre.y(), 23.5 * 0.05, 0.06);
  EXPECT_EQ(set->snapshots[1].map_index, 1);
  EXPECT_NEAR(set->snapshots[1].centre.x(), 75.5 * 0.05, 0.06);
  EXPECT_EQ(set->snapshots[0].cells, 36);  // the outline
  // One common patch size; the box's inside is unobserved, the floor around it observed.
  const scene::Patch& p = set->snapshots[0].patch;
  EXPECT_EQ(p.width, set->snapshots[1].patch.width);
  EXPECT_EQ(p.weight.size(), p.occupancy.size());
  EXPECT_EQ(p.WeightAt(p.width / 2, p.height / 2), 0.0f);
  EXPECT_EQ(p.WeightAt(0, 0), 1.0f);
}

TEST(SnapshotExtractorTest, TouchingObjectsMergeIntoOneSnapshot) {
  grid::OccupancyGrid a = Room(), b = Room();
  AddBox(&a, 30, 30, 10, 8);
  AddBox(&a, 40, 30, 10, 8);  // shares no free cell with the first
  AddBox(&a, 30, 70, 10, 8);  // a clear gap of 10 cells from the others
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, b}, SnapshotOptions{});
  ASSERT_TRUE(set.ok()) << set.status();
  ASSERT_EQ(set->snapshots.size(), 2u);
  // Region growing walks the first two as one region (64 outline cells), the third alone (32).
  EXPECT_EQ(set->snapshots[0].cells, 64);
  EXPECT_EQ(set->snapshots[1].cells, 32);
}

// A solid piece of furniture, as floor-plan data sets draw it.
void AddSolid(grid::OccupancyGrid* map, int x0, int y0, int w, int h) {
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) map->at(x, y) = grid::kOccupiedValue;
  }
}

TEST(SnapshotExtractorTest, ALargeChangedRegionIsSplitIntoObjects) {
  grid::OccupancyGrid a = Room(), b = Room();
  // A row of three desks (24 x 12 cells) two cells apart (linked by region growing) and a lone
  // table: with max_region_cells 500 the row is too large to be one object.
  AddSolid(&a, 10, 40, 24, 12);
  AddSolid(&a, 36, 40, 24, 12);
  AddSolid(&a, 62, 40, 24, 12);
  AddSolid(&a, 20, 90, 16, 16);
  SnapshotOptions options;
  options.max_region_cells = 500;
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, b}, options);
  ASSERT_TRUE(set.ok()) << set.status();
  ASSERT_EQ(set->snapshots.size(), 4u);  // three desks and the table, none ignored
  int desks = 0;
  for (const Snapshot& s : set->snapshots) desks += s.cells == 24 * 12;
  EXPECT_EQ(desks, 3);
  ASSERT_FALSE(set->warnings.empty());
  EXPECT_THAT(set->warnings[0], HasSubstr("split into 3 parts"));
}

TEST(SnapshotExtractorTest, SmallObjectsAreKeptWhenTheyRecur) {
  grid::OccupancyGrid a = Room(), b = Room(), c = Room();
  // A bin of 5 cells (a plus sign, below min_region_cells 8) moves between the three maps.
  auto bin = [](grid::OccupancyGrid* map, int x, int y) {
    for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      map->at(x + dx, y + dy) = grid::kOccupiedValue;
    }
  };
  bin(&a, 30, 30);
  bin(&b, 80, 40);
  bin(&c, 50, 90);
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, b, c}, SnapshotOptions{});
  ASSERT_TRUE(set.ok()) << set.status();
  ASSERT_EQ(set->snapshots.size(), 3u);
  EXPECT_EQ(set->per_map, (std::vector<int>{1, 1, 1}));
  EXPECT_EQ(set->snapshots[0].cells, 5);
  // Everything small is dropped with the old behaviour (small_region_cells 0).
  SnapshotOptions old;
  old.small_region_cells = 0;
  EXPECT_TRUE(ExtractSnapshots({a, b, c}, old)->snapshots.empty());
}

// Issue 36: a small piece that shows in one map only is an object when it is compact and nothing
// else changed near it; SLAM specks, scattered or strung along a line, are not.
TEST(SnapshotExtractorTest, IsolatedSmallObjectIsFoundAndSpecksAreNot) {
  // A table leg or a bin: 2 x 3 cells (10 x 15 cm), in map a only.
  grid::OccupancyGrid a = Room();
  AddSolid(&a, 60, 60, 2, 3);
  const StatusOr<SnapshotSet> lone = ExtractSnapshots({a, Room()}, SnapshotOptions{});
  ASSERT_TRUE(lone.ok()) << lone.status();
  ASSERT_EQ(lone->snapshots.size(), 1u);
  EXPECT_EQ(lone->snapshots[0].cells, 6);
  EXPECT_THAT(lone->warnings.back(), HasSubstr("isolation_radius_m"));
  SnapshotOptions recurrence_only;
  recurrence_only.isolation_radius_m = 0.0;
  EXPECT_TRUE(ExtractSnapshots({a, Room()}, recurrence_only)->snapshots.empty());

  // The same piece with three single-cell specks within 0.5 m (the filter removes the specks,
  // but they say this part of the map is noisy): not an object.
  grid::OccupancyGrid noisy = a;
  for (const auto& [x, y] : {std::pair{54, 58}, {66, 64}, {61, 69}}) {
    noisy.at(x, y) = grid::kOccupiedValue;
  }
  EXPECT_TRUE(ExtractSnapshots({noisy, Room()}, SnapshotOptions{})->snapshots.empty());

  // A strand of 6 cells along a row (a scan line's specks): compact it is not.
  grid::OccupancyGrid strand = Room();
  AddSolid(&strand, 40, 80, 6, 1);
  EXPECT_TRUE(ExtractSnapshots({strand, Room()}, SnapshotOptions{})->snapshots.empty());
}

// A 3-cell blob is what a speck leaves at any resolution; speckle leaves such blobs in every map,
// so one of its size in another map is no evidence of an object: specks that "recur" are not
// objects, unless the operator asks for 3-cell regions (small_region_cells 3).
TEST(SnapshotExtractorTest, ThreeCellSpecksThatRecurAreNotObjects) {
  grid::OccupancyGrid a = Room(), b = Room();
  // An L of 3 cells (it passes the low-pass filter whole), far from anything else, two per map.
  auto speck = [](grid::OccupancyGrid* map, int x, int y) {
    for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {0, 1}}) {
      map->at(x + dx, y + dy) = grid::kOccupiedValue;
    }
  };
  speck(&a, 30, 30);
  speck(&a, 80, 80);
  speck(&b, 30, 85);
  speck(&b, 85, 30);
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, b}, SnapshotOptions{});
  ASSERT_TRUE(set.ok()) << set.status();
  EXPECT_TRUE(set->snapshots.empty());
  SnapshotOptions three;
  three.small_region_cells = 3;
  const StatusOr<SnapshotSet> kept = ExtractSnapshots({a, b}, three);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_EQ(kept->snapshots.size(), 4u);  // the test can fail: with 3, each has a twin
}

TEST(SnapshotExtractorTest, BadInputsAreErrors) {
  const grid::OccupancyGrid a = Room();
  EXPECT_THAT(ExtractSnapshots({a}, SnapshotOptions{}).status().message(),
              HasSubstr("at least two maps"));
  grid::OccupancyGrid smaller(100, 120, 0.05, Pose2{}, grid::kFreeValue);
  const Status size = ExtractSnapshots({a, smaller}, SnapshotOptions{}).status();
  EXPECT_EQ(size.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(size.message(), HasSubstr("map 1"));
  EXPECT_THAT(size.message(), HasSubstr("size"));
  grid::OccupancyGrid coarser(120, 120, 0.1, Pose2{}, grid::kFreeValue);
  EXPECT_THAT(ExtractSnapshots({a, coarser}, SnapshotOptions{}).status().message(),
              HasSubstr("resolution"));
  grid::OccupancyGrid shifted(120, 120, 0.05, Pose2{1.0, 0.0, 0.0}, grid::kFreeValue);
  EXPECT_THAT(ExtractSnapshots({a, shifted}, SnapshotOptions{}).status().message(),
              HasSubstr("origin"));
  SnapshotOptions bad;
  bad.filter_threshold = 2.0;
  EXPECT_THAT(ExtractSnapshots({a, a}, bad).status().message(),
              HasSubstr("snapshots.filter_threshold"));
}

TEST(SnapshotExtractorTest, NoDifferenceGivesAnEmptyModel) {
  const grid::OccupancyGrid a = Room();
  const StatusOr<SnapshotSet> set = ExtractSnapshots({a, a, a}, SnapshotOptions{});
  ASSERT_TRUE(set.ok());
  EXPECT_TRUE(set->snapshots.empty());
  const StatusOr<LearnedModel> model = LearnObjects({a, a, a});
  ASSERT_TRUE(model.ok());
  EXPECT_EQ(model->num_objects, 0);
  EXPECT_EQ(model->num_templates, 0);
  ASSERT_EQ(model->warnings.size(), 1u);
  EXPECT_THAT(model->warnings[0], HasSubstr("no object moved"));
}

}  // namespace
}  // namespace fleetmap::object_learning
