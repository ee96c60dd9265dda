#include "bench/register/growing_experiment.hpp"

#include <gtest/gtest.h>

namespace fleetmap::bench {
namespace {

GrowingPairOutcome Outcome(const std::string& group, int bar_at, bool bar_right, int seq_at,
                           bool seq_right) {
  GrowingPairOutcome p;
  p.group = group;
  p.bar_only = {bar_at, bar_right};
  p.sequential = {seq_at, seq_right};
  return p;
}

TEST(GrowingExperimentTest, SummarizesPlacementsWrongOnesAndTheirStepPerRule) {
  const std::vector<GrowingPairOutcome> pairs = {
      Outcome("maps", 4, true, 3, true), Outcome("maps", 0, false, 5, true),
      Outcome("maps", 0, false, 0, false), Outcome("repeated", 2, false, 2, false)};
  const std::vector<GrowingSummaryRow> rows = SummarizeGrowing(pairs);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].group, "maps");
  EXPECT_EQ(rows[0].pairs, 3);
  EXPECT_EQ(rows[0].bar_only.placed, 1);
  EXPECT_EQ(rows[0].sequential.placed, 2);
  EXPECT_EQ(rows[0].sequential.wrong, 0);
  EXPECT_DOUBLE_EQ(rows[0].sequential.mean_step, 4.0);
  EXPECT_EQ(rows[1].bar_only.wrong, 1);
  EXPECT_EQ(rows[2].group, "");
  EXPECT_EQ(rows[2].pairs, 4);
  EXPECT_EQ(rows[2].sequential.placed, 3);
  EXPECT_EQ(rows[2].sequential.wrong, 1);
}

TEST(GrowingExperimentTest, RegistersEveryStepAndPlacesAGrowingOfficeMapRightly) {
  StatusOr<std::vector<SourceMap>> maps = SyntheticSourceMaps(1, 3);  // an office
  ASSERT_TRUE(maps.ok()) << maps.status();
  GrowingBenchOptions options;
  options.pairs.overlaps = {0.7};
  options.pairs.pairs_per_overlap = 1;
  options.pairs.drift = false;
  options.steps = 3;
  const GrowingBenchRun run = RunGrowingBench(*maps, options, nullptr);
  ASSERT_EQ(run.pairs.size(), 1u);
  const GrowingPairOutcome& pair = run.pairs.front();
  ASSERT_EQ(pair.confidence.size(), 3u);
  ASSERT_EQ(pair.seconds.size(), 3u);
  // The full-grown B at 70 % overlap is the pair bench's easy case: right and verified.
  EXPECT_TRUE(pair.right.back());
  EXPECT_TRUE(pair.verified.back());
  // Whatever the bar alone places, the sequential test places too, no later, and rightly.
  if (pair.bar_only.placed_at > 0) {
    EXPECT_GT(pair.sequential.placed_at, 0);
    EXPECT_LE(pair.sequential.placed_at, pair.bar_only.placed_at);
  }
  EXPECT_GT(pair.sequential.placed_at, 0);
  EXPECT_TRUE(pair.sequential.right);
}

}  // namespace
}  // namespace fleetmap::bench
