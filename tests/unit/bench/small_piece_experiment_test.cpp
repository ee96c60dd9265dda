#include "bench/objects/small_piece_experiment.hpp"

#include <gtest/gtest.h>

namespace fleetmap::bench {
namespace {

// Without specks, small pieces that show in one map only are found only by the lone rule.
TEST(SmallPieceExperimentTest, LonePiecesAreFoundOnlyWithTheLoneRule) {
  SmallPieceOptions options;
  options.pairs = 2;
  options.small_in_one_map = true;
  options.speck_events_per_100m2 = 0.0;
  const StatusOr<SmallPieceResult> lone = RunSmallPieceExperiment(options);
  ASSERT_TRUE(lone.ok()) << lone.status();
  EXPECT_EQ(lone->small, 2 * options.small_pieces);
  EXPECT_EQ(lone->small_found, lone->small);
  EXPECT_EQ(lone->furniture_found, lone->furniture);
  EXPECT_EQ(lone->false_objects, 0);
  EXPECT_EQ(lone->noise_snapshots, 0);
  options.snapshots.isolation_radius_m = 0.0;
  const StatusOr<SmallPieceResult> recurrence_only = RunSmallPieceExperiment(options);
  ASSERT_TRUE(recurrence_only.ok());
  EXPECT_EQ(recurrence_only->small_found, 0);
}

// Specks in noise-only pairs: what is kept is counted, and strands and scatters mostly are not.
TEST(SmallPieceExperimentTest, NoiseOnlyPairsCountFalseObjects) {
  SmallPieceOptions options;
  options.pairs = 3;
  options.speck_events_per_100m2 = 20.0;
  const StatusOr<SmallPieceResult> result = RunSmallPieceExperiment(options);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->noise_area_m2, 3 * 293.04, 0.1);
  // 20 events per 100 m2 in each of 2 maps: about 117 events per pair; far fewer are objects.
  EXPECT_LT(result->noise_snapshots, 3 * 117 / 4);
  options.pairs = 0;
  EXPECT_FALSE(RunSmallPieceExperiment(options).ok());
}

}  // namespace
}  // namespace fleetmap::bench
