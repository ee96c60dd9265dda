#include "bench/extrapolation/room_segmentation.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "bench/extrapolation/floor_plan.hpp"
#include "bench/extrapolation/floor_plan_experiment.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {
namespace {

constexpr double kResolution = 0.05;

// Two 4 m x 3 m rooms side by side, a 0.15 m wall between them with a 0.9 m doorway
// (y in [1.0, 1.9)), walls all round; nothing unknown.
grid::OccupancyGrid TwoRooms() {
  grid::OccupancyGrid map(168, 64, kResolution, Pose2{0.0, 0.0, 0.0}, grid::kOccupiedValue);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 c = map.CellCenter(x, y);
      const bool in_rows = c.y() > 0.1 && c.y() < 3.1;
      const bool room_a = c.x() > 0.1 && c.x() < 4.1;
      const bool room_b = c.x() > 4.25 && c.x() < 8.25;
      const bool doorway = c.x() >= 4.1 && c.x() <= 4.25 && c.y() > 1.0 && c.y() < 1.9;
      if ((in_rows && (room_a || room_b)) || doorway) map.at(x, y) = grid::kFreeValue;
    }
  }
  return map;
}

TEST(RoomSegmentationTest, FindsBothRoomsAndTheirDoorway) {
  const grid::OccupancyGrid map = TwoRooms();
  const RoomSegmentation seg = SegmentRooms(map, RoomSegmentationOptions{});
  ASSERT_EQ(seg.room_area.size(), 2u);
  for (double area : seg.room_area) EXPECT_NEAR(area, 12.0, 0.3);
  // Each room is behind one doorway: both are kept, each opening onto the other.
  ASSERT_EQ(seg.doorways.size(), 2u);
  for (const SegmentedDoorway& door : seg.doorways) {
    EXPECT_NE(door.room, door.other);
    EXPECT_NEAR(door.width, 0.9, 0.06);
    for (const Point2& jamb : {door.jamb_a, door.jamb_b}) {
      EXPECT_GE(jamb.x(), 4.0);
      EXPECT_LE(jamb.x(), 4.35);
      EXPECT_GE(jamb.y(), 0.97);
      EXPECT_LE(jamb.y(), 1.93);
    }
    // The room's cells lie on the side `into_room` points to.
    const size_t some_room_cell = [&] {
      for (size_t i = 0; i < seg.labels.size(); ++i) {
        if (seg.labels[i] == door.room) return i;
      }
      return seg.labels.size();
    }();
    ASSERT_LT(some_room_cell, seg.labels.size());
    const Point2 inside = map.CellCenter(static_cast<int>(some_room_cell % map.width()),
                                         static_cast<int>(some_room_cell / map.width()));
    const bool room_is_left = inside.x() < 4.1;
    EXPECT_EQ(door.into_room.x() < 0.0, room_is_left);
    EXPECT_NEAR(std::abs(door.into_room.x()), 1.0, 1e-6);
  }
}

TEST(RoomSegmentationTest, TooNarrowPassageIsNoDoorway) {
  grid::OccupancyGrid map = TwoRooms();
  // Narrow the doorway to 0.4 m: the rooms stay apart, and the passage is no door.
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 c = map.CellCenter(x, y);
      if (c.x() >= 4.1 && c.x() <= 4.25 && c.y() > 1.4 && c.y() < 1.9) {
        map.at(x, y) = grid::kOccupiedValue;
      }
    }
  }
  const RoomSegmentation seg = SegmentRooms(map, RoomSegmentationOptions{});
  ASSERT_EQ(seg.room_area.size(), 2u);
  EXPECT_TRUE(seg.doorways.empty());
}

TEST(RoomSegmentationTest, SceneHidesExactlyTheRoomsFreeCells) {
  const grid::OccupancyGrid map = TwoRooms();
  const RoomSegmentationOptions options;
  const RoomSegmentation seg = SegmentRooms(map, options);
  ASSERT_FALSE(seg.doorways.empty());
  const SegmentedDoorway& doorway = seg.doorways.front();
  const FloorPlan plan = PlanForRoom(map, seg, doorway, options);
  sim::Random random(1);
  const HiddenRoomScene scene = HideRoom(plan, plan.doors.front(), false, 0.0, &random);
  std::vector<uint8_t> is_leaf(seg.labels.size(), 0);
  for (size_t i : doorway.leaf_cells) is_leaf[i] = 1;
  int64_t hidden = 0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const size_t i = static_cast<size_t>(y) * map.width() + x;
      const std::optional<grid::CellIndex> cell = scene.local.CellAt(map.CellCenter(x, y));
      ASSERT_TRUE(cell.has_value());
      const grid::CellState state = scene.local.StateAt(cell->x, cell->y);
      if (map.StateAt(x, y) != grid::CellState::kFree) continue;
      if (seg.labels[i] == doorway.room) {
        EXPECT_EQ(state, grid::CellState::kUnknown) << x << "," << y;
        ++hidden;
      } else if (is_leaf[i]) {
        EXPECT_EQ(state, grid::CellState::kOccupied) << x << "," << y;
      } else {
        EXPECT_EQ(state, grid::CellState::kFree) << x << "," << y;
      }
    }
  }
  EXPECT_NEAR(hidden * kResolution * kResolution, 12.0, 0.3);
  // The door closes the doorway, hinge at jamb a.
  EXPECT_FALSE(scene.door.open);
  EXPECT_TRUE(scene.door.hinge.isApprox(doorway.jamb_a));
  EXPECT_TRUE(scene.door.latch.isApprox(doorway.jamb_b));
}

// A real map's unknown cells have no ground truth: PlanForRoom labels them so, and a prediction on
// them is neither right nor wrong.
TEST(RoomSegmentationTest, PredictionsOnCellsTheMapNeverSawAreUnscored) {
  grid::OccupancyGrid map = TwoRooms();
  const grid::CellIndex unscanned{2, 2};  // a wall corner nobody scanned
  map.at(unscanned.x, unscanned.y) = grid::kUnknownValue;
  const RoomSegmentationOptions options;
  const RoomSegmentation seg = SegmentRooms(map, options);
  ASSERT_FALSE(seg.doorways.empty());
  const FloorPlan plan = PlanForRoom(map, seg, seg.doorways.front(), options);
  const std::optional<grid::CellIndex> in_plan =
      plan.truth.CellAt(map.CellCenter(unscanned.x, unscanned.y));
  ASSERT_TRUE(in_plan.has_value());
  EXPECT_EQ(plan.labels[static_cast<size_t>(in_plan->y) * plan.truth.width() + in_plan->x],
            kPlanUnknown);

  // The hidden room's cells more than 0.8 m past its doorway become cells the scans never reached:
  // the robot's map is the same (hidden either way), only the truth is gone.
  const PlanDoor& door = plan.doors.front();
  const Point2 doorway = 0.5 * (door.jamb_a + door.jamb_b);
  FloorPlan unscanned_end = plan;
  for (int y = 0; y < plan.truth.height(); ++y) {
    for (int x = 0; x < plan.truth.width(); ++x) {
      int32_t& label = unscanned_end.labels[static_cast<size_t>(y) * plan.truth.width() + x];
      if (label == door.room && (plan.truth.CellCenter(x, y) - doorway).dot(door.into_room) > 0.8) {
        label = kPlanUnknown;
      }
    }
  }
  FloorPlanExperimentOptions experiment;
  experiment.dropout = 0.0;
  const auto whole = RunHiddenRoomExperiment(plan, experiment);
  const auto cut = RunHiddenRoomExperiment(unscanned_end, experiment);
  ASSERT_TRUE(whole.ok() && cut.ok());
  ASSERT_EQ(whole->size(), cut->size());
  int64_t unscored = 0;
  for (size_t r = 0; r < whole->size(); ++r) {
    for (size_t k = 0; k < experiment.p_th.size(); ++k) {
      const PlanDoorScore& a = (*whole)[r].scores[k];
      const PlanDoorScore& b = (*cut)[r].scores[k];
      EXPECT_EQ(a.unscored, 0);
      EXPECT_EQ(b.false_free, a.false_free) << "unscanned cells are never counted wrong";
      EXPECT_EQ(b.true_free + b.unscored, a.true_free);
      unscored += b.unscored;
    }
  }
  EXPECT_GT(unscored, 0) << "the prediction reaches more than 0.8 m into the room";
}

// A 4 x 3 m room A and, east of it through a 1.15 m doorway, a room B 1.6 m wide whose east wall
// the scans never reached, in a map with 2 m of unknown all round: the building's edge is B's east
// side.
grid::OccupancyGrid RoomAtTheEdge() {
  grid::OccupancyGrid map(248, 144, kResolution, Pose2{-2.0, -2.0, 0.0}, grid::kUnknownValue);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 c = map.CellCenter(x, y);
      const bool walls = c.x() > 0.0 && c.x() < 5.85 && c.y() > 0.0 && c.y() < 3.2;
      const bool in_rows = c.y() > 0.1 && c.y() < 3.1;
      const bool room_a = c.x() > 0.1 && c.x() < 4.1;
      const bool room_b = c.x() > 4.25 && c.x() < 5.85;
      const bool doorway = c.x() >= 4.1 && c.x() <= 4.25 && c.y() > 0.95 && c.y() < 2.1;
      if (walls) map.at(x, y) = grid::kOccupiedValue;
      if ((in_rows && (room_a || room_b)) || doorway) map.at(x, y) = grid::kFreeValue;
    }
  }
  return map;
}

TEST(RoomSegmentationTest, BuildingIsTheKnownSpaceWithItsHolesFilled) {
  grid::OccupancyGrid map = RoomAtTheEdge();
  const std::optional<grid::CellIndex> hole = map.CellAt(Point2(2.0, 1.5));
  ASSERT_TRUE(hole.has_value());
  map.at(hole->x, hole->y) = grid::kUnknownValue;  // unscanned, inside room A
  const std::vector<uint8_t> building = SegmentBuilding(map, 1.0);
  const auto inside = [&](double x, double y) {
    const std::optional<grid::CellIndex> c = map.CellAt(Point2(x, y));
    return building[static_cast<size_t>(c->y) * map.width() + c->x] != 0;
  };
  EXPECT_TRUE(inside(2.0, 1.5));   // the hole
  EXPECT_TRUE(inside(5.0, 1.5));   // room B
  EXPECT_FALSE(inside(6.0, 1.5));  // beyond B's unseen east wall
  EXPECT_FALSE(inside(-1.0, 1.5));
  EXPECT_FALSE(inside(3.0, 4.0));
}

// Strict scoring: a prediction on a cell the map never saw is wrong outside the building (and
// still unscored inside it).
TEST(RoomSegmentationTest, StrictScoringCountsPredictionsOutsideTheBuildingWrong) {
  const grid::OccupancyGrid map = RoomAtTheEdge();
  const RoomSegmentationOptions options;
  const RoomSegmentation seg = SegmentRooms(map, options);
  const auto door = std::find_if(seg.doorways.begin(), seg.doorways.end(),
                                 [](const SegmentedDoorway& d) { return d.into_room.x() > 0.5; });
  ASSERT_NE(door, seg.doorways.end()) << "room B, behind the doorway from A";
  const std::vector<uint8_t> building = SegmentBuilding(map, options.building_closing);
  const FloorPlan strict = PlanForRoom(map, seg, *door, options, building);
  const FloorPlan lenient = PlanForRoom(map, seg, *door, options);
  FloorPlanExperimentOptions experiment;
  experiment.dropout = 0.0;
  const auto strict_scores = RunHiddenRoomExperiment(strict, experiment);
  const auto lenient_scores = RunHiddenRoomExperiment(lenient, experiment);
  ASSERT_TRUE(strict_scores.ok() && lenient_scores.ok());
  ASSERT_EQ(strict_scores->size(), lenient_scores->size());
  int64_t outside = 0;
  for (size_t r = 0; r < strict_scores->size(); ++r) {
    for (size_t k = 0; k < experiment.p_th.size(); ++k) {
      const PlanDoorScore& a = (*strict_scores)[r].scores[k];
      const PlanDoorScore& b = (*lenient_scores)[r].scores[k];
      EXPECT_EQ(a.true_free, b.true_free);
      EXPECT_EQ(b.unknown_outside, 0);
      EXPECT_EQ(a.false_free, b.false_free + a.unknown_outside);
      EXPECT_EQ(a.unscored + a.unknown_outside, b.unscored);
      EXPECT_LE(a.unknown_outside, a.outside_building);
      outside += a.unknown_outside;
    }
  }
  EXPECT_GT(outside, 0) << "the prediction runs past B's unseen east wall";
}

}  // namespace
}  // namespace fleetmap::bench
