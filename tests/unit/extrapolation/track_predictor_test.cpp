#include "common/extrapolation/track_predictor.hpp"

#include <gtest/gtest.h>

namespace fleetmap::extrapolation {
namespace {

scene::PersonTrack Walk(bool left, bool entered) {
  scene::PersonTrack track;

  for (int i = 0; i <= 10; ++i) track.points.push_back({0.2 * i, Point2(0.2 * i, 1.0), 0.0});
  track.left_view = left;
  track.entered_view = entered;
  return track;  // 1 m/s along +x from (0, 1) to (2, 1)
}

TEST(TrackPredictorTest, ObservedTrackIsDensified) {
  const auto poses = SweepTrack(Walk(false, false), {});
  ASSERT_FALSE(poses.empty());
  EXPECT_TRUE(poses.front().position.isApprox(Point2(0, 1)));
  EXPECT_TRUE(poses.back().position.isApprox(Point2(2, 1)));
  for (size_t i = 1; i < poses.size(); ++i) {
    EXPECT_LE((poses[i].position - poses[i - 1].position).norm(), 0.1 + 1e-9);
    EXPECT_FALSE(poses[i].predicted);
  }
}

TEST(TrackPredictorTest, ExtendsForwardOnLeaving) {
  TrackPredictorOptions options;
  options.horizon = 1.5;
  const auto poses = SweepTrack(Walk(true, false), options);
  EXPECT_TRUE(poses.back().predicted);
  EXPECT_NEAR(poses.back().position.x(), 3.5, 1e-6);  // 2 m + 1.5 s * 1 m/s
  EXPECT_NEAR(poses.back().position.y(), 1.0, 1e-6);
  EXPECT_TRUE(poses.front().position.isApprox(Point2(0, 1)));
}

TEST(TrackPredictorTest, ExtendsBackwardOnEntering) {
  TrackPredictorOptions options;
  options.horizon = 1.5;
  const auto poses = SweepTrack(Walk(false, true), options);
  EXPECT_TRUE(poses.front().predicted);
  EXPECT_NEAR(poses.front().position.x(), -1.5, 1e-6);
  EXPECT_FALSE(poses.back().predicted);
  EXPECT_NEAR(poses.back().position.x(), 2.0, 1e-6);
}

TEST(TrackPredictorTest, StandingStillPredictsNothing) {
  scene::PersonTrack track;
  track.left_view = true;
  track.points = {{0.0, Point2(1, 1), 0.0}, {1.0, Point2(1, 1), 0.0}};
  for (const SweptPose& pose : SweepTrack(track, {})) EXPECT_FALSE(pose.predicted);
}

TEST(TrackPredictorTest, OnePointGivesNothing) {
  scene::PersonTrack track;
  track.points = {{0.0, Point2(1, 1), 0.0}};
  EXPECT_TRUE(SweepTrack(track, {}).empty());
}

}  // namespace
}  // namespace fleetmap::extrapolation
