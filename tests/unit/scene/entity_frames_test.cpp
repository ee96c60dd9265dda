#include "common/scene/entity_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace fleetmap::scene {
namespace {

// A quarter turn about the origin, then 10 m along x: (1, 0) goes to (10, 1).
Transform2 QuarterTurnThenShift() { return Pose2{10.0, 0.0, std::numbers::pi / 2}.ToTransform(); }

TEST(EntityFramesTest, MovesADoorsJambsAndTurnsItsOpeningDirection) {
  DoorEntity door;
  door.id = "d1";
  door.hinge = Point2(1.0, 0.0);
  door.latch = Point2(2.0, 0.0);
  door.opening_direction = Vector2::UnitY();
  const auto moved = std::get<DoorEntity>(ToFleetFrame(door, QuarterTurnThenShift()));
  EXPECT_NEAR(moved.hinge.x(), 10.0, 1e-12);
  EXPECT_NEAR(moved.hinge.y(), 1.0, 1e-12);
  EXPECT_NEAR(moved.latch.y(), 2.0, 1e-12);
  EXPECT_NEAR(moved.opening_direction.x(), -1.0, 1e-12);
  EXPECT_NEAR(moved.opening_direction.y(), 0.0, 1e-12);
  EXPECT_EQ(moved.id, "d1");
}

TEST(EntityFramesTest, TurnsStairsAndPersonHeadingsWithTheFrame) {
  StairsEntity stairs;
  stairs.position = Point2(0.0, 1.0);
  stairs.ascending = Vector2::UnitX();
  const auto moved_stairs = std::get<StairsEntity>(ToFleetFrame(stairs, QuarterTurnThenShift()));
  EXPECT_NEAR(moved_stairs.position.x(), 9.0, 1e-12);
  EXPECT_NEAR(moved_stairs.ascending.y(), 1.0, 1e-12);

  PersonTrack track;
  track.points.push_back({1.0, Point2(0.0, 0.0), std::numbers::pi / 2});
  const auto moved_track = std::get<PersonTrack>(ToFleetFrame(track, QuarterTurnThenShift()));
  ASSERT_EQ(moved_track.points.size(), 1U);
  EXPECT_NEAR(std::abs(moved_track.points[0].heading), std::numbers::pi, 1e-12);
  EXPECT_NEAR(moved_track.points[0].position.x(), 10.0, 1e-12);
}

TEST(EntityFramesTest, SameEntityComparesKindIdAndEveryValue) {
  DoorEntity door;
  door.id = "d1";
  DoorEntity opened = door;
  opened.open = true;
  StairsEntity stairs;
  stairs.id = "d1";
  EXPECT_TRUE(SameEntity(door, door));
  EXPECT_FALSE(SameEntity(door, opened));
  EXPECT_FALSE(SameEntity(door, stairs));

  PersonTrack track;
  track.id = "p";
  track.points.push_back({1.0, Point2(1.0, 2.0), 0.0});
  PersonTrack later = track;
  later.points[0].stamp = 2.0;
  EXPECT_TRUE(SameEntity(track, track));
  EXPECT_FALSE(SameEntity(track, later));
}

TEST(EntityFramesTest, EntityIdReadsTheIdOfAnyKind) {
  PersonTrack track;
  track.id = "walker";
  EXPECT_EQ(EntityId(Entity(track)), "walker");
}

}  // namespace
}  // namespace fleetmap::scene
