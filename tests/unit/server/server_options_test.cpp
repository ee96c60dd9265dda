#include <gtest/gtest.h>

#include <string>

#include "common/core/options_printer.hpp"
#include "server/server_node.hpp"

namespace fleetmap::server {
namespace {

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ServerOptionsTest, TheDefaultsAreValid) { EXPECT_TRUE(ServerOptions{}.Validate().ok()); }

// Validate() reaches the options nested three levels down, naming the part they belong to.
TEST(ServerOptionsTest, ValidateRecursesIntoEveryPartThatRuns) {
  ServerOptions bad_threshold;
  bad_threshold.prediction.extrapolation.p_th = 1.5;
  const Status prediction = bad_threshold.Validate();
  ASSERT_FALSE(prediction.ok());
  EXPECT_TRUE(Contains(prediction.message(), "map extrapolation")) << prediction;
  EXPECT_TRUE(Contains(prediction.message(), "p_th")) << prediction;

  ServerOptions bad_learning;
  bad_learning.learning.learn.em.annealing = 1.5;
  const Status learning = bad_learning.Validate();
  ASSERT_FALSE(learning.ok());
  EXPECT_TRUE(Contains(learning.message(), "object learning")) << learning;
  EXPECT_TRUE(Contains(learning.message(), "em.annealing")) << learning;

  ServerOptions bad_tiles;
  bad_tiles.map.fusion.tile_size = -1.0;
  EXPECT_FALSE(bad_tiles.Validate().ok());
}

// One placement bar: the server places a robot exactly when Register finds the match, at the
// registration module's bar (the one `fleetmap register` uses by default).
TEST(ServerOptionsTest, PlacesAtTheRegistrationPlacementBar) {
  const ServerOptions options;
  EXPECT_EQ(options.map.placement.registration.min_confidence, registration::kPlacementConfidence);
  EXPECT_TRUE(Contains(DescribeOptions(options), "    min_confidence: 0.95\n"))
      << DescribeOptions(options);
  ServerOptions bad;
  bad.map.placement.registration.min_confidence = 1.5;
  EXPECT_FALSE(bad.Validate().ok());
}

// The sequential wins under the bar are off unless the operator asks, and checked when asked.
TEST(ServerOptionsTest, PlacesUnderTheBarOnlyWhenAskedAndChecksTheAsking) {
  const ServerOptions options;
  EXPECT_EQ(options.map.placement.sequential_wins, 0);
  EXPECT_TRUE(Contains(DescribeOptions(options), "sequential_wins: 0\n"))
      << DescribeOptions(options);
  ServerOptions negative;
  negative.map.placement.sequential_wins = -1;
  EXPECT_FALSE(negative.Validate().ok());
  ServerOptions above_one;
  above_one.map.placement.sequential_wins = 3;
  above_one.map.placement.sequential_confidence = 1.5;
  const Status refused = above_one.Validate();
  EXPECT_FALSE(refused.ok());
  EXPECT_TRUE(Contains(std::string(refused.message()), "sequential_confidence"));
  ServerOptions asked;
  asked.map.placement.sequential_wins = 3;
  EXPECT_TRUE(asked.Validate().ok());
}

TEST(ServerOptionsTest, APartSwitchedOffIsNotChecked) {
  ServerOptions options;
  options.prediction.enabled = false;
  options.prediction.extrapolation.p_th = 1.5;
  EXPECT_TRUE(options.Validate().ok());
}

// The start-up log shows every part, nested under its name.
TEST(ServerOptionsTest, DescribeShowsTheNestedOptions) {
  ServerOptions options;
  options.transforms[RobotId{"alpha"}] = Pose2{1.0, 2.0, 0.5};
  const std::string text = DescribeOptions(options);
  EXPECT_TRUE(Contains(text, "map:\n  fusion:\n    tile_size: 10\n")) << text;
  EXPECT_TRUE(Contains(text, "  admission:\n    max_clock_ahead: 30 s\n")) << text;
  EXPECT_TRUE(Contains(text, "prediction:\n  enabled: true\n  extrapolation:\n    p_th: 0.5\n"))
      << text;
  EXPECT_TRUE(Contains(text, "    em:\n      sigma: 0.25\n")) << text;
  EXPECT_TRUE(Contains(text, "transforms: {alpha: [1, 2, 0.5]}\n")) << text;
}

}  // namespace
}  // namespace fleetmap::server
