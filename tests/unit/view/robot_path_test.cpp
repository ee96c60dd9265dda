#include "view/robot_path.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace fleetmap::view {
namespace {

using nlohmann::json;

const Pose2 kGiven{0.0, 0.0, 0.0};
const Pose2 kPlaced{0.0, 5.0, 0.0};

TEST(RobotPathTest, PointsCloserThanTheSpacingAreSkippedWithinARun) {
  RobotPath path(10, 0.5);
  path.Add(Point2(0.0, 0.0), kGiven);
  path.Add(Point2(0.2, 0.0), kGiven);
  path.Add(Point2(0.6, 0.0), kGiven);
  EXPECT_EQ(path.Json(), json::parse("[[0.0, 0.0, 0.6, 0.0]]"));
  // A new frame starts a run at once, however close its first point.
  path.Add(Point2(0.7, 0.0), kPlaced);
  EXPECT_EQ(path.Json(), json::parse("[[0.0, 0.0, 0.6, 0.0], [0.7, 0.0]]"));
}

TEST(RobotPathTest, TheOldestPointsGoFirstAndAnEmptiedRunWithThem) {
  RobotPath path(3, 0.1);
  path.Add(Point2(0.0, 0.0), kGiven);
  path.Add(Point2(1.0, 0.0), kGiven);
  path.Add(Point2(1.0, 5.0), kPlaced);
  path.Add(Point2(2.0, 5.0), kPlaced);
  EXPECT_EQ(path.Json(), json::parse("[[1.0, 0.0], [1.0, 5.0, 2.0, 5.0]]"));
  path.Add(Point2(3.0, 5.0), kPlaced);
  EXPECT_EQ(path.Json(), json::parse("[[1.0, 5.0, 2.0, 5.0, 3.0, 5.0]]"));
}

TEST(RobotPathTest, TheGainedPointsSayWhereANewRunBegins) {
  RobotPath path(10, 0.1);
  EXPECT_FALSE(path.TakeGained().has_value());
  path.Add(Point2(0.0, 0.0), kGiven);
  EXPECT_EQ(path.TakeGained(), json::parse("[[], [0.0, 0.0]]"));
  path.Add(Point2(1.0, 0.0), kGiven);
  path.Add(Point2(1.0, 5.0), kPlaced);
  EXPECT_EQ(path.TakeGained(), json::parse("[[1.0, 0.0], [1.0, 5.0]]"));
  EXPECT_FALSE(path.TakeGained().has_value()) << "taken";
}

}  // namespace
}  // namespace fleetmap::view
