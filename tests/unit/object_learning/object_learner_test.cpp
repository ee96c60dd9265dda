#include "common/object_learning/object_learner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace fleetmap::object_learning {
namespace {

using ::testing::HasSubstr;

// A 5 x 5 m room with box outlines (insides unknown) at the given cells.
grid::OccupancyGrid Room(const std::vector<std::pair<int, int>>& boxes) {
  grid::OccupancyGrid map(100, 100, 0.05, Pose2{}, grid::kFreeValue);
  for (int i = 0; i < 100; ++i) {
    map.at(i, 0) = map.at(i, 99) = map.at(0, i) = map.at(99, i) = grid::kOccupiedValue;
  }
  for (const auto& [x0, y0] : boxes) {
    for (int y = y0; y < y0 + 8; ++y) {
      for (int x = x0; x < x0 + 12; ++x) {
        const bool edge = x == x0 || y == y0 || x == x0 + 11 || y == y0 + 7;
        map.at(x, y) = edge ? grid::kOccupiedValue : grid::kUnknownValue;
      }
    }
  }
  return map;
}

TEST(ObjectLearnerTest, LearnsBoxesWithAssignmentsForEverySnapshot) {
  const std::vector<grid::OccupancyGrid> maps = {Room({{10, 10}, {60, 60}}),
                                                 Room({{30, 70}, {70, 20}}), Room({{15, 50}})};
  const StatusOr<LearnedModel> model = LearnObjects(maps);
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_GE(model->num_objects, 2);
  EXPECT_EQ(model->num_templates, 1);  // every box alike
  ASSERT_EQ(model->snapshots.size(), 5u);
  EXPECT_EQ(model->objects.size(), static_cast<size_t>(model->num_objects));
  EXPECT_EQ(model->object_template.size(), model->objects.size());
  // Mutual exclusion: the two boxes of map 0 are two objects.
  EXPECT_NE(model->snapshots[0].object, model->snapshots[1].object);
  for (const scene::Patch& p : model->objects) {
    for (float v : p.occupancy) {
      EXPECT_GE(v, 0.0f);
      EXPECT_LE(v, 1.0f);
    }
  }
  EXPECT_FALSE(model->searched.empty());
  EXPECT_TRUE(model->warnings.empty());
}

TEST(ObjectLearnerTest, ACancelledRunStopsWithUnavailable) {
  const std::vector<grid::OccupancyGrid> maps = {Room({{10, 10}, {60, 60}}),
                                                 Room({{30, 70}, {70, 20}})};
  const std::atomic<bool> cancel{true};
  LearnOptions options;
  options.cancel = &cancel;
  const StatusOr<LearnedModel> model = LearnObjects(maps, options);
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), StatusCode::kUnavailable);
  EXPECT_THAT(model.status().message(), HasSubstr("cancelled"));
}

TEST(ObjectLearnerTest, ApproximateEStepAboveTheBoundIsSaid) {
  const std::vector<grid::OccupancyGrid> maps = {Room({{10, 10}, {60, 60}}),
                                                 Room({{30, 70}, {70, 20}})};
  LearnOptions options;
  options.em.max_exact_snapshots = 1;  // two snapshots per map: sampled
  const StatusOr<LearnedModel> model = LearnObjects(maps, options);
  ASSERT_TRUE(model.ok()) << model.status();
  ASSERT_FALSE(model->warnings.empty());
  EXPECT_THAT(model->warnings.back(), HasSubstr("Gibbs"));
  EXPECT_NE(model->snapshots[0].object, model->snapshots[1].object);
}

TEST(ObjectLearnerTest, ATightMemoryBudgetDegradesAndSaysSo) {
  const std::vector<grid::OccupancyGrid> maps = {
      Room({{10, 10}, {60, 60}}), Room({{30, 70}, {70, 20}}), Room({{15, 50}}), Room({{50, 30}})};
  LearnOptions options;
  options.restarts = 2;
  options.memory_budget_mb = 0.05;  // far below what four maps need: every step is taken
  const StatusOr<LearnedModel> model = LearnObjects(maps, options);
  ASSERT_TRUE(model.ok()) << model.status();  // degraded, never failed
  EXPECT_TRUE(model->degraded);
  std::string all;
  for (const std::string& w : model->warnings) all += w + "\n";
  EXPECT_THAT(all, HasSubstr("memory budget"));
  EXPECT_THAT(all, HasSubstr("one random start"));
  EXPECT_THAT(all, HasSubstr("left out (fewer sessions)"));
  // The oldest maps went first: what is left comes from the newest two.
  for (const SnapshotAssignment& s : model->snapshots) EXPECT_GE(s.map_index, 2);
  EXPECT_GE(model->num_objects, 1);
}

TEST(ObjectLearnerTest, AnAmpleBudgetChangesNothing) {
  const std::vector<grid::OccupancyGrid> maps = {Room({{10, 10}, {60, 60}}),
                                                 Room({{30, 70}, {70, 20}})};
  const StatusOr<LearnedModel> model = LearnObjects(maps);
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_FALSE(model->degraded);
  EXPECT_GT(model->estimated_memory_mb, 0.0);
  EXPECT_LT(model->estimated_memory_mb, LearnOptions{}.memory_budget_mb);
}

TEST(ObjectLearnerTest, ProgressIsReportedWithStagesInOrder) {
  const std::vector<grid::OccupancyGrid> maps = {Room({{10, 10}, {60, 60}}),
                                                 Room({{30, 70}, {70, 20}}), Room({{15, 50}})};
  std::vector<LearnProgress> reports;
  LearnOptions options;
  options.progress = [&reports](const LearnProgress& p) { reports.push_back(p); };
  const StatusOr<LearnedModel> model = LearnObjects(maps, options);
  ASSERT_TRUE(model.ok()) << model.status();
  ASSERT_GE(reports.size(), 3u);
  EXPECT_EQ(reports.front().stage, LearnStage::kExtracting);
  EXPECT_EQ(reports.back().stage, LearnStage::kDone);
  bool searched = false, iterated = false;
  for (size_t i = 1; i < reports.size(); ++i) {
    EXPECT_LE(static_cast<int>(reports[i - 1].stage), static_cast<int>(reports[i].stage));
    EXPECT_LE(reports[i - 1].candidates_done, reports[i].candidates_done);
    EXPECT_LE(reports[i - 1].elapsed_seconds, reports[i].elapsed_seconds);
    EXPECT_EQ(reports[i].maps, 3);
    if (reports[i].stage == LearnStage::kSearching) {
      searched = true;
      EXPECT_EQ(reports[i].snapshots, 5);
      EXPECT_GE(reports[i].num_objects, 2);
      EXPECT_GE(reports[i].candidates_estimate, reports[i].candidates_done + 1);
      iterated = iterated || reports[i].em_iteration > 0;
    }
  }
  EXPECT_TRUE(searched);
  EXPECT_TRUE(iterated);
  EXPECT_EQ(reports.back().candidates_done, static_cast<int>(model->searched.size()));
  EXPECT_EQ(reports.back().num_objects, model->num_objects);
  EXPECT_THAT(DescribeProgress(reports[reports.size() / 2]), HasSubstr("EM iteration"));
}

TEST(ObjectLearnerTest, ObjectPoseUndoesTheAlignment) {
  SnapshotAssignment s;
  s.centre = Point2(2.0, 3.0);
  s.alignment = {0.1, 0.0, 0.0};  // the snapshot is moved +0.1 m in x onto the object
  Pose2 pose = ObjectPoseInMap(s);
  EXPECT_NEAR(pose.x, 1.9, 1e-12);
  EXPECT_NEAR(pose.y, 3.0, 1e-12);
  EXPECT_NEAR(pose.yaw, 0.0, 1e-12);
  // Turned a quarter onto the object, then shifted: the object's x axis is the snapshot's -y.
  s.alignment = {0.0, 0.2, 1.5707963267948966};
  pose = ObjectPoseInMap(s);
  EXPECT_NEAR(pose.yaw, -1.5707963267948966, 1e-12);
  EXPECT_NEAR(pose.x, 2.0 - 0.2, 1e-12);  // R(-90 deg) (0, 0.2) = (0.2, 0)
  EXPECT_NEAR(pose.y, 3.0, 1e-12);
}

TEST(ObjectLearnerTest, BadInputsAreErrors) {
  const grid::OccupancyGrid a = Room({{10, 10}});
  const Status one = LearnObjects({a}).status();
  EXPECT_EQ(one.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(one.message(), HasSubstr("at least two maps"));
  LearnOptions options;
  options.em.annealing = 1.5;
  EXPECT_THAT(LearnObjects({a, a}, options).status().message(), HasSubstr("em.annealing"));
  options = LearnOptions{};
  options.restarts = 0;
  EXPECT_THAT(LearnObjects({a, a}, options).status().message(), HasSubstr("restarts"));
}

}  // namespace
}  // namespace fleetmap::object_learning
