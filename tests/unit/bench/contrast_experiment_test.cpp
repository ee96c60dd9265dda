#include "bench/objects/contrast_experiment.hpp"

#include <gtest/gtest.h>

#include <set>

namespace fleetmap::bench {
namespace {

TEST(ContrastExperimentTest, ThePapersSetUpComesFirstAndEveryOtherConditionChangesIt) {
  const std::vector<ContrastCondition> conditions = ContrastConditions();
  ASSERT_GE(conditions.size(), 4u);
  const ContrastCondition& paper = conditions.front();
  EXPECT_EQ(paper.name, "paper");
  EXPECT_EQ(paper.data.plan.shapes.size(), 4u);  // two chairs, a bin, a box
  EXPECT_EQ(paper.data.plan.sessions, 9);
  std::set<std::string> names;
  for (const ContrastCondition& c : conditions) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_FALSE(c.changed.empty()) << c.name;
    if (&c == &paper) continue;
    const bool data_differs = c.data.plan.shapes != paper.data.plan.shapes ||
                              c.data.plan.sessions != paper.data.plan.sessions ||
                              c.data.size != paper.data.size;
    const bool learning_differs =
        c.learn.em.sigma_initial != paper.learn.em.sigma_initial ||
        c.learn.em.rotation_scan_step != paper.learn.em.rotation_scan_step ||
        c.learn.snapshots.blur_cells != paper.learn.snapshots.blur_cells;
    EXPECT_TRUE(data_differs || learning_differs) << c.name;
  }
}

// The paper's set-up on one data set, a few starts: both models reach the true partition from
// these starts (docs/results.md: 19 and 19 of 20 on data seed 1), counted over both models' runs.
TEST(ContrastExperimentTest, CountsGoodStartsOfBothModelsFromTheSameStarts) {
  const ContrastCondition paper = ContrastConditions().front();
  ContrastRunOptions run;
  run.data_sets = 1;
  run.starts = 2;
  run.cross_validate = false;
  const StatusOr<ContrastRow> row = RunContrastCondition(paper, run);
  ASSERT_TRUE(row.ok()) << row.status();
  EXPECT_EQ(row->condition, "paper");
  EXPECT_EQ(row->starts, 2);
  EXPECT_EQ(row->maps, 9);
  EXPECT_EQ(row->true_objects, 4);
  EXPECT_EQ(row->true_templates, 3);
  EXPECT_EQ(row->hierarchical.train_log_likelihood.size(), 2u);
  EXPECT_EQ(row->flat.train_log_likelihood.size(), 2u);
  EXPECT_EQ(row->hierarchical.good, 2);
  EXPECT_EQ(row->flat.good, 2);
}

// Equally good optima are counted against the best start, whatever its rank.
TEST(ContrastExperimentTest, NearBestCountsTheStartsWithinToleranceOfTheBest) {
  EXPECT_EQ(NearBest({9795.6, 9794.4, 9650.0, 9798.0}, 5.0), 3);
  EXPECT_EQ(NearBest({9795.6, 9794.4, 9650.0, 9798.0}, 1.0), 1);
  EXPECT_EQ(NearBest({-3.0, -200.0}, 5.0), 1);
  EXPECT_EQ(NearBest({}, 5.0), 0);
}

TEST(ContrastExperimentTest, AConditionNoLabCanHoldIsAnError) {
  ContrastCondition crowded = ContrastConditions().front();
  crowded.data.size = 4.0;
  crowded.data.plan.shapes.assign(30, sim::MovableShape::kBox);
  crowded.data.plan.max_present = 30;
  crowded.data.plan.min_present = 30;
  ContrastRunOptions run;
  run.data_sets = 1;
  run.starts = 1;
  const StatusOr<ContrastRow> row = RunContrastCondition(crowded, run);
  ASSERT_FALSE(row.ok());
  EXPECT_EQ(row.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(row.status().message().find("no free place"), std::string::npos) << row.status();
}

}  // namespace
}  // namespace fleetmap::bench
