#include "common/scene/submap_graph.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>

namespace fleetmap::scene {
namespace {

TEST(SubmapGraphTest, RelativePoseIsTheSecondPoseSeenFromTheFirst) {
  const Pose2 map_from_a{2.0, 0.0, std::numbers::pi / 2};
  const Pose2 map_from_b{2.0, 3.0, std::numbers::pi / 2};
  const Pose2 a_T_b = RelativePose(map_from_a, map_from_b);
  // b is 3 m "up" in the map, which is a's +x after a's quarter turn.
  EXPECT_NEAR(a_T_b.x, 3.0, 1e-12);
  EXPECT_NEAR(a_T_b.y, 0.0, 1e-12);
  EXPECT_NEAR(a_T_b.yaw, 0.0, 1e-12);
}

TEST(SubmapGraphTest, FindReturnsTheSubmapWithThatIdOrNull) {
  SubmapGraph graph;
  graph.submaps.resize(2);
  graph.submaps[0].id = 4;
  graph.submaps[1].id = 9;
  ASSERT_NE(graph.Find(9), nullptr);
  EXPECT_EQ(graph.Find(9), &graph.submaps[1]);
  EXPECT_EQ(graph.Find(5), nullptr);
}

TEST(SubmapGraphTest, NamesMatchTheJsonAndTopicSpelling) {
  EXPECT_EQ(SubmapKindName(SubmapKind::kPredictedDoor), "predicted_door");
  EXPECT_EQ(std::string(SubmapStateName(SubmapState::kRetracted)), "retracted");
  EXPECT_EQ(std::string(SubmapStateName(SubmapState::kObserved)), "observed");
}

}  // namespace
}  // namespace fleetmap::scene
