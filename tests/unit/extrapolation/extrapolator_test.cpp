#include "common/extrapolation/extrapolator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <set>
#include <utility>

#include "common/extrapolation/prediction_check.hpp"
#include "common/extrapolation/submap_graph_json.hpp"
#include "tests/unit/extrapolation/test_maps.hpp"

namespace fleetmap::extrapolation {
namespace {

using testing::Corridor;
using testing::CorridorWithRooms;
using testing::DoorAt;
using testing::Fill;
using ::testing::HasSubstr;
using testing::kRes;

scene::DoorEntity Door() {
  scene::DoorEntity door;
  door.id = "door_1";
  door.hinge = Point2(4.0, 2.075);
  door.latch = Point2(5.0, 2.075);
  door.opening_direction = Vector2(0, 1);
  return door;
}

std::vector<Point2> FreeCellsInMap(const scene::Submap& submap) {
  std::vector<Point2> out;
  for (int y = 0; y < submap.navigable.height(); ++y) {
    for (int x = 0; x < submap.navigable.width(); ++x) {
      if (submap.navigable.StateAt(x, y) == grid::CellState::kFree) {
        out.push_back(submap.map_from_submap.ToTransform() * submap.navigable.CellCenter(x, y));
      }
    }
  }
  return out;
}

// Whether the sub-map's grid is free at a map-frame point.
bool FreeAt(const scene::Submap& submap, const Point2& map_point) {
  const auto cell =
      submap.navigable.CellAt(submap.map_from_submap.ToTransform().inverse() * map_point);
  return cell && submap.navigable.StateAt(cell->x, cell->y) == grid::CellState::kFree;
}

int64_t FreeCount(const grid::OccupancyGrid& grid) { return grid.CountStates().free; }

TEST(ExtrapolatorTest, NoDoorGivesOnePlace) {
  const grid::OccupancyGrid map = CorridorWithRooms();
  const auto result = Extrapolate(map, {});
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->graph.submaps.size(), 1u);
  EXPECT_TRUE(result->graph.edges.empty());
  const scene::Submap& observed = result->graph.submaps[0];
  EXPECT_EQ(observed.kind, scene::SubmapKind::kObserved);
  EXPECT_EQ(observed.place, 0u);
  EXPECT_EQ(FreeCount(observed.navigable), FreeCount(map));
  // A map without free cells still has its observed sub-map.
  const auto unknown = Extrapolate(grid::OccupancyGrid(20, 10, kRes), {});
  ASSERT_TRUE(unknown.ok());
  ASSERT_EQ(unknown->graph.submaps.size(), 1u);
  EXPECT_EQ(unknown->graph.submaps[0].kind, scene::SubmapKind::kObserved);
  EXPECT_EQ(FreeCount(unknown->graph.submaps[0].navigable), 0);
}

TEST(ExtrapolatorTest, OpenDoorsSplitTheObservedMapIntoPlaces) {
  const grid::OccupancyGrid map = CorridorWithRooms();
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_a", 2.0, 3.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_b", 7.0, 6.0, 2.075, true));
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok()) << result.status();
  const scene::SubmapGraph& graph = result->graph;
  ASSERT_EQ(graph.submaps.size(), 3u);
  int64_t free = 0;
  for (uint32_t id = 0; id < 3; ++id) {
    const scene::Submap& s = graph.submaps[id];
    EXPECT_EQ(s.id, id);
    EXPECT_EQ(s.place, id);
    EXPECT_EQ(s.kind, scene::SubmapKind::kObserved);
    EXPECT_TRUE(s.map_from_submap.ToTransform().isApprox(Transform2::Identity()));
    free += FreeCount(s.navigable);
  }
  EXPECT_EQ(free, FreeCount(map));  // every free cell in exactly one place
  // Numbered by their first cell, row-major from the origin: the corridor, then the rooms.
  EXPECT_TRUE(FreeAt(graph.submaps[0], Point2(5.0, 1.0)));
  EXPECT_TRUE(FreeAt(graph.submaps[1], Point2(1.0, 4.0)));
  EXPECT_TRUE(FreeAt(graph.submaps[2], Point2(8.0, 4.0)));
  EXPECT_FALSE(FreeAt(graph.submaps[0], Point2(1.0, 4.0)));
  EXPECT_FALSE(FreeAt(graph.submaps[1], Point2(5.0, 1.0)));
  for (const Point2& p : FreeCellsInMap(graph.submaps[1])) {
    EXPECT_GT(p.y(), 2.0);
    EXPECT_LT(p.x(), 4.9);
  }
  ASSERT_EQ(graph.edges.size(), 2u);
  EXPECT_EQ(graph.edges[0].from, 0u);
  EXPECT_EQ(graph.edges[0].to, 1u);
  EXPECT_EQ(graph.edges[0].entity_id, "door_a");
  EXPECT_TRUE(graph.edges[0].from_T_to.ToTransform().isApprox(Transform2::Identity()));
  EXPECT_EQ(graph.edges[1].from, 0u);
  EXPECT_EQ(graph.edges[1].to, 2u);
  EXPECT_EQ(graph.edges[1].entity_id, "door_b");
  EXPECT_THAT(graph.submaps[0].entity_ids, ::testing::ElementsAre("door_a", "door_b"));
  EXPECT_THAT(graph.submaps[2].entity_ids, ::testing::ElementsAre("door_b"));
}

TEST(ExtrapolatorTest, ClosedDoorSeparatesPlacesToo) {
  const grid::OccupancyGrid map = CorridorWithRooms();  // room b mapped before the door shut
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_a", 2.0, 3.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_b", 6.0, 7.0, 2.075, false));
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok()) << result.status();
  const scene::SubmapGraph& graph = result->graph;
  ASSERT_EQ(graph.submaps.size(), 4u);
  EXPECT_EQ(graph.submaps[2].kind, scene::SubmapKind::kObserved);
  EXPECT_EQ(graph.submaps[3].kind, scene::SubmapKind::kPredictedDoor);
  EXPECT_EQ(graph.submaps[3].place, 3u);
  ASSERT_EQ(graph.edges.size(), 3u);
  EXPECT_EQ(graph.edges[1].from, 0u);  // corridor - room b, through the closed door
  EXPECT_EQ(graph.edges[1].to, 2u);
  EXPECT_EQ(graph.edges[1].entity_id, "door_b");
  EXPECT_EQ(graph.edges[2].from, 0u);  // the prediction opens from the corridor
  EXPECT_EQ(graph.edges[2].to, 3u);
  EXPECT_EQ(graph.edges[2].entity_id, "door_b");
}

TEST(ExtrapolatorTest, PredictedSubmapJoinsThePlaceItsDoorOpensFrom) {
  // A closed door in room b's far wall, opening north into the unseen.
  const grid::OccupancyGrid map = CorridorWithRooms();
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_a", 2.0, 3.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_b", 6.0, 7.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_c", 7.0, 8.0, 6.075, false));
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok()) << result.status();
  const scene::SubmapGraph& graph = result->graph;
  ASSERT_EQ(graph.submaps.size(), 4u);
  const scene::Submap& predicted = graph.submaps[3];
  EXPECT_EQ(predicted.kind, scene::SubmapKind::kPredictedDoor);
  EXPECT_NE(predicted.place, graph.submaps[2].place);
  ASSERT_EQ(graph.edges.size(), 3u);
  EXPECT_EQ(graph.edges[2].from, 2u);  // room b
  EXPECT_EQ(graph.edges[2].to, 3u);
  EXPECT_EQ(graph.edges[2].entity_id, "door_c");
  EXPECT_THAT(graph.submaps[2].entity_ids, ::testing::ElementsAre("door_b", "door_c"));
}

TEST(ExtrapolatorTest, GraphJsonListsPlacesAndObservedEdges) {
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_a", 2.0, 3.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_b", 6.0, 7.0, 2.075, false));
  const auto result = Extrapolate(CorridorWithRooms(), entities);
  ASSERT_TRUE(result.ok());
  const nlohmann::json json = SubmapGraphToJson(result->graph);
  ASSERT_EQ(json["places"].size(), 4u);
  EXPECT_EQ(json["places"][1]["place"], 1);
  EXPECT_EQ(json["places"][1]["observed"], true);
  EXPECT_EQ(json["places"][1]["submaps"], nlohmann::json::array({1}));
  EXPECT_EQ(json["places"][3]["observed"], false);
  EXPECT_EQ(json["submaps"][1]["kind"], "observed");
  EXPECT_EQ(json["edges"][0]["entity"], "door_a");
  EXPECT_EQ(json["edges"][0]["to"], 1);
}

TEST(ExtrapolatorTest, FootOfStairsSeparatesPlaces) {
  // The corridor's free cells run on past the foot of a flight at x = 6 (the steps).
  scene::StairsEntity stairs;
  stairs.id = "stairs_1";
  stairs.position = Point2(6.0, 1.075);
  stairs.ascending = Vector2(1, 0);
  stairs.step_width = 1.85;
  stairs.run_length = 3.0;
  scene::Entities entities;
  entities.stairs.push_back(stairs);
  const auto result = Extrapolate(Corridor(), entities);
  ASSERT_TRUE(result.ok()) << result.status();
  const scene::SubmapGraph& graph = result->graph;
  ASSERT_EQ(graph.submaps.size(), 3u);
  EXPECT_TRUE(FreeAt(graph.submaps[0], Point2(2.0, 1.0)));
  EXPECT_TRUE(FreeAt(graph.submaps[1], Point2(8.0, 1.0)));
  EXPECT_EQ(graph.submaps[2].kind, scene::SubmapKind::kPredictedStairs);
  ASSERT_EQ(graph.edges.size(), 2u);
  EXPECT_EQ(graph.edges[0].from, 0u);
  EXPECT_EQ(graph.edges[0].to, 1u);
  EXPECT_EQ(graph.edges[1].from, 0u);  // the flight goes up from the floor before its foot
  EXPECT_EQ(graph.edges[1].to, 2u);
  EXPECT_EQ(graph.edges[1].entity_id, "stairs_1");
}

TEST(ExtrapolatorTest, SpeckleDoesNotMakePlaces) {
  grid::OccupancyGrid map = CorridorWithRooms();
  Fill(&map, 4.9, 2.15, 5.05, 6.0, grid::kUnknownValue);
  // Isolated free cells in the unknown beyond the rooms, a free cell in a wall, and a small
  // nook (0.2 x 0.2 m) behind a third doorway.
  Fill(&map, 0, 6.15, 10, 8.0, grid::kUnknownValue);
  for (int i = 0; i < 40; ++i) {
    const double x = 0.3 + 0.24 * i, y = 6.5 + 0.03 * (i % 40);
    Fill(&map, x, y, x + 0.05, y + 0.05, grid::kFreeValue);
  }
  Fill(&map, 4.95, 3.0, 5.0, 3.05, grid::kFreeValue);
  scene::Entities entities;
  for (double x : {1.0, 3.5, 6.5}) {
    const std::string id = "door_" + std::to_string(static_cast<int>(x * 10));
    entities.doors.push_back(DoorAt(id, x, x + 0.3, 6.075, true));
  }
  Fill(&map, 6.5, 6.0, 6.8, 6.15, grid::kFreeValue);
  Fill(&map, 6.55, 6.15, 6.75, 6.35, grid::kFreeValue);  // 16 cells, well under 0.5 m2
  ExtrapolationOptions no_minimum;
  no_minimum.min_place_area = 1e-4;
  const auto speckled = Extrapolate(map, entities, no_minimum);
  ASSERT_TRUE(speckled.ok());
  ASSERT_GT(speckled->graph.submaps.size(), 40u);  // the test can fail
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->graph.submaps.size(), 1u);
  EXPECT_TRUE(FreeAt(result->graph.submaps[0], Point2(6.6, 6.3)));     // the nook joins
  EXPECT_FALSE(FreeAt(result->graph.submaps[0], Point2(0.32, 6.52)));  // speckle is dropped
}

TEST(ExtrapolatorTest, PeoplesCellsJoinThePlaceTheyFallIn) {
  const grid::OccupancyGrid map = CorridorWithRooms();
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_a", 2.0, 3.0, 2.075, true));
  entities.doors.push_back(DoorAt("door_b", 6.0, 7.0, 2.075, true));
  scene::PersonTrack person;
  person.id = "p1";
  for (int i = 0; i <= 10; ++i) person.points.push_back({0.2 * i, Point2(6.0 + 0.2 * i, 4.0), 0});
  entities.people.push_back(person);
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->graph.submaps.size(), 3u);
  EXPECT_THAT(result->graph.submaps[2].entity_ids, ::testing::Contains("p1"));
  EXPECT_THAT(result->graph.submaps[0].entity_ids, ::testing::Not(::testing::Contains("p1")));
  const grid::OccupancyGrid& cf = result->conditionally_free;
  int64_t claimed = 0;
  for (int y = 0; y < cf.height(); ++y) {
    for (int x = 0; x < cf.width(); ++x) {
      if (cf.StateAt(x, y) != grid::CellState::kFree) continue;
      ++claimed;
      EXPECT_TRUE(FreeAt(result->graph.submaps[2], cf.CellCenter(x, y)));
    }
  }
  EXPECT_GT(claimed, 50);
}

TEST(ExtrapolatorTest, ClosedDoorMakesAPredictedSubmapBehindIt) {
  const grid::OccupancyGrid map = Corridor();
  scene::Entities entities;
  entities.doors.push_back(Door());
  ExtrapolationOptions options;
  const auto result = Extrapolate(map, entities, options);
  ASSERT_TRUE(result.ok()) << result.status();
  const scene::SubmapGraph& graph = result->graph;
  ASSERT_EQ(graph.submaps.size(), 2u);
  ASSERT_EQ(graph.edges.size(), 1u);
  const scene::Submap& observed = graph.submaps[0];
  const scene::Submap& predicted = graph.submaps[1];
  EXPECT_EQ(observed.kind, scene::SubmapKind::kObserved);
  EXPECT_EQ(predicted.kind, scene::SubmapKind::kPredictedDoor);
  EXPECT_NE(predicted.place, observed.place);
  EXPECT_EQ(predicted.entity_ids, std::vector<std::string>{"door_1"});
  EXPECT_EQ(graph.edges[0].from, 0u);
  EXPECT_EQ(graph.edges[0].to, predicted.id);
  EXPECT_EQ(graph.edges[0].entity_id, "door_1");
  // The sub-map sits d behind the door's centre, its +y into the room.
  EXPECT_NEAR(predicted.map_from_submap.x, 4.5, 1e-9);
  EXPECT_NEAR(predicted.map_from_submap.y, 2.075 + options.door_submap_distance, 1e-9);
  EXPECT_NEAR(graph.edges[0].from_T_to.y, predicted.map_from_submap.y, 1e-9);

  const std::vector<Point2> free = FreeCellsInMap(predicted);
  ASSERT_GT(free.size(), 200u);
  for (const Point2& p : free) {
    EXPECT_GT(p.y(), 2.15);  // behind the door, past the wall
    EXPECT_LE((p - Point2(4.5, 2.075)).norm(), options.door_max_range + 1e-9);
    const auto cell = map.CellAt(p);
    ASSERT_TRUE(cell);
    EXPECT_NE(map.StateAt(cell->x, cell->y), grid::CellState::kOccupied);
  }
  // Centred on the doorway (not the hinge): as much space on the hinge's side as on the latch's.
  int hinge_side = 0, latch_side = 0;
  for (const Point2& p : free) (p.x() < 4.5 ? hinge_side : latch_side)++;
  EXPECT_NEAR(hinge_side, latch_side, 0.02 * free.size());
  ASSERT_EQ(predicted.confidence.size(), static_cast<size_t>(predicted.navigable.cell_count()));
}

TEST(ExtrapolatorTest, KnownWallStopsTheDoorPrediction) {
  grid::OccupancyGrid map = Corridor();
  scene::Entities entities;
  entities.doors.push_back(Door());
  auto beyond_wall = [](const scene::Submap& s) {
    int n = 0;
    for (const Point2& p : FreeCellsInMap(s)) n += p.x() < 3.6;
    return n;
  };
  const auto open_room = Extrapolate(map, entities);
  ASSERT_TRUE(open_room.ok());
  ASSERT_GT(beyond_wall(open_room->graph.submaps[1]), 0);  // the test can fail
  Fill(&map, 3.6, 2.15, 3.75, 8.0, grid::kOccupiedValue);  // a wall the robot saw earlier
  const auto walled = Extrapolate(map, entities);
  ASSERT_TRUE(walled.ok());
  EXPECT_EQ(beyond_wall(walled->graph.submaps[1]), 0);
}

// Two closed doors in the corridor's wall lead to two rooms: a door's prediction stops where its
// room can first end, 0.2 m short of the other doorway's near jamb (x = 5.9), and a door in another
// wall does not cut it.
TEST(ExtrapolatorTest, NextClosedDoorInTheSameWallBoundsThePrediction) {
  const grid::OccupancyGrid map = Corridor();
  scene::Entities alone;
  alone.doors.push_back(Door());  // x in [4, 5]
  scene::Entities two = alone;
  two.doors.push_back(DoorAt("door_2", 5.9, 6.8, 2.075, false));
  const auto past_limit = [](const scene::Submap& s) {
    int n = 0;
    for (const Point2& p : FreeCellsInMap(s)) n += p.x() > 5.7 + kRes;  // wholly past it
    return n;
  };
  const auto short_of_it = [](const scene::Submap& s) {  // past halfway (x = 5.425), the old rule
    int n = 0;
    for (const Point2& p : FreeCellsInMap(s)) n += p.x() > 5.425 + 0.5 * kRes && p.x() < 5.65;
    return n;
  };
  const auto one = Extrapolate(map, alone);
  const auto both = Extrapolate(map, two);
  ASSERT_TRUE(one.ok() && both.ok());
  const auto door_1 = [](const ExtrapolationResult& r) {
    return *std::find_if(r.graph.submaps.begin(), r.graph.submaps.end(), [](const auto& s) {
      return s.kind == scene::SubmapKind::kPredictedDoor && s.entity_ids.front() == "door_1";
    });
  };
  EXPECT_GT(past_limit(door_1(*one)), 0);  // the test can fail
  EXPECT_EQ(past_limit(door_1(*both)), 0);
  EXPECT_GT(short_of_it(door_1(*both)), 0);  // the room may reach past halfway
  EXPECT_GT(FreeCellsInMap(door_1(*both)).size(), 200u);
  // A door on the corridor's other wall (opening the other way) is another wall's door.
  scene::Entities across = alone;
  scene::DoorEntity facing = DoorAt("door_3", 6.2, 7.1, 0.075, false);
  facing.opening_direction = Vector2(0, -1);
  across.doors.push_back(facing);
  const auto with_facing = Extrapolate(map, across);
  ASSERT_TRUE(with_facing.ok());
  EXPECT_EQ(FreeCellsInMap(door_1(*with_facing)).size(), FreeCellsInMap(door_1(*one)).size());
}

// A hidden room (x in [1.5, 4.7), y in [2.15, 5), unknown) above Corridor(), behind a closed door
// at x in [3.7, 4.6), with a second, open doorway (y in [3, 3.9)) in its 0.3 m right wall into a
// neighbour room the robot mapped (x in [5, 8)): it saw that room, the recess of the doorway and
// the faces of the walls from inside.
grid::OccupancyGrid RoomWithTwoDoors() {
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 5.0, 2.15, 8.0, 5.0, grid::kFreeValue);
  Fill(&map, 4.95, 2.15, 5.0, 5.0, grid::kOccupiedValue);
  Fill(&map, 5.0, 5.0, 8.0, 5.05, grid::kOccupiedValue);
  Fill(&map, 8.0, 2.15, 8.05, 5.05, grid::kOccupiedValue);
  Fill(&map, 4.7, 3.0, 5.0, 3.9, grid::kFreeValue);
  return map;
}

std::set<std::pair<int64_t, int64_t>> CellKeys(const std::vector<Point2>& points) {
  std::set<std::pair<int64_t, int64_t>> keys;
  for (const Point2& p : points) {
    keys.emplace(std::llround(p.x() / kRes - 0.5), std::llround(p.y() / kRes - 0.5));
  }
  return keys;
}

// A bound takes exactly the cells it excludes: the walkability opening judges the room before the
// next door's limit cuts it, so the corners the cut makes are not rounded off.
TEST(ExtrapolatorTest, TheNextDoorsLimitTakesOnlyTheCellsPastIt) {
  const grid::OccupancyGrid map = Corridor();
  scene::Entities alone;
  alone.doors.push_back(Door());  // x in [4, 5]
  scene::Entities two = alone;
  two.doors.push_back(DoorAt("door_2", 5.9, 6.8, 2.075, false));  // limit at x = 5.7
  const auto one = Extrapolate(map, alone);
  const auto both = Extrapolate(map, two);
  ASSERT_TRUE(one.ok() && both.ok());
  const auto door_1_cells = [](const ExtrapolationResult& r) {
    const auto s =
        std::find_if(r.graph.submaps.begin(), r.graph.submaps.end(), [](const auto& submap) {
          return submap.kind == scene::SubmapKind::kPredictedDoor &&
                 submap.entity_ids.front() == "door_1";
        });
    return FreeCellsInMap(*s);
  };
  std::vector<Point2> short_of_limit;
  int past = 0;
  for (const Point2& p : door_1_cells(*one)) {
    if (p.x() < 5.7) {  // the limit lies on a cell edge: the cells short of it
      short_of_limit.push_back(p);
    } else {
      ++past;
    }
  }
  ASSERT_GT(past, 0);  // the limit cuts the room
  EXPECT_EQ(CellKeys(door_1_cells(*both)), CellKeys(short_of_limit));
}

TEST(ExtrapolatorTest, DoorPredictionNeverClaimsObservedFreeSpace) {
  const grid::OccupancyGrid map = RoomWithTwoDoors();
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_1", 3.7, 4.6, 2.075, false));
  for (double p_th : {0.5, 0.6, 0.7}) {
    ExtrapolationOptions options;
    options.p_th = p_th;
    const auto result = Extrapolate(map, entities, options);
    ASSERT_TRUE(result.ok()) << result.status();
    const scene::Submap& predicted = result->graph.submaps.back();
    ASSERT_EQ(predicted.kind, scene::SubmapKind::kPredictedDoor);
    const std::vector<Point2> free = FreeCellsInMap(predicted);
    EXPECT_GT(free.size(), 100u) << p_th;
    int on_observed = 0;
    for (const Point2& p : free) {
      const auto cell = map.CellAt(p);
      ASSERT_TRUE(cell);
      on_observed += map.StateAt(cell->x, cell->y) != grid::CellState::kUnknown;
    }
    // The doorway's recess and the neighbour room are another place, not the predicted one.
    EXPECT_EQ(on_observed, 0) << p_th;
  }
}

TEST(ExtrapolatorTest, EitherJambAsTheHingeGivesTheSamePrediction) {
  for (const grid::OccupancyGrid& map : {Corridor(), RoomWithTwoDoors()}) {
    scene::Entities entities, swapped;
    entities.doors.push_back(DoorAt("door_1", 3.7, 4.6, 2.075, false));
    swapped.doors.push_back(DoorAt("door_1", 4.6, 3.7, 2.075, false));
    const auto a = Extrapolate(map, entities);
    const auto b = Extrapolate(map, swapped);
    ASSERT_TRUE(a.ok() && b.ok());
    const auto cells_a = CellKeys(FreeCellsInMap(a->graph.submaps.back()));
    const auto cells_b = CellKeys(FreeCellsInMap(b->graph.submaps.back()));
    ASSERT_GT(cells_a.size(), 100u);
    std::vector<std::pair<int64_t, int64_t>> differ;
    std::set_symmetric_difference(cells_a.begin(), cells_a.end(), cells_b.begin(), cells_b.end(),
                                  std::back_inserter(differ));
    EXPECT_LE(differ.size(), cells_a.size() / 100);
  }
}

TEST(ExtrapolatorTest, UnseenThickWallIsNotPredictedFree) {
  // The hidden room's right wall is 0.3 m thick (x in [5, 5.3)); the robot saw only its face
  // from the neighbour room. The door's latch is 0.1 m from that wall.
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 5.3, 2.15, 8.0, 5.0, grid::kFreeValue);
  Fill(&map, 5.25, 2.15, 5.3, 5.0, grid::kOccupiedValue);
  scene::Entities entities;
  entities.doors.push_back(DoorAt("door_1", 4.0, 4.9, 2.075, false));
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok());
  int in_wall = 0, beside_wall = 0;
  for (const Point2& p : FreeCellsInMap(result->graph.submaps.back())) {
    in_wall += p.x() >= 5.0;
    beside_wall += p.x() >= 4.5 && p.x() < 5.0;
  }
  EXPECT_EQ(in_wall, 0);
  EXPECT_GT(beside_wall, 50);  // the room up to the wall is still predicted
}

TEST(ExtrapolatorTest, PredictionDoesNotLeakThroughAGapNarrowerThanAPerson) {
  // A wall the robot saw earlier beside the door (x in [5, 5.1)), unknown on both sides, with a
  // gap at y in [2.8, 2.8 + gap).
  auto beyond = [](double gap) {
    grid::OccupancyGrid map = Corridor();
    Fill(&map, 5.0, 2.15, 5.1, 6.0, grid::kOccupiedValue);
    Fill(&map, 5.0, 2.8, 5.1, 2.8 + gap, grid::kUnknownValue);
    scene::Entities entities;
    entities.doors.push_back(DoorAt("door_1", 4.0, 4.9, 2.075, false));
    const auto result = Extrapolate(map, entities);
    EXPECT_TRUE(result.ok());
    int n = 0;
    for (const Point2& p : FreeCellsInMap(result->graph.submaps.back())) n += p.x() >= 5.1;
    return n;
  };
  EXPECT_EQ(beyond(0.3), 0);
  EXPECT_GT(beyond(0.8), 0);  // a doorway-wide gap is a way through: the test can fail
}

TEST(ExtrapolatorTest, HigherThresholdPredictsLess) {
  const grid::OccupancyGrid map = Corridor();
  scene::Entities entities;
  entities.doors.push_back(Door());
  size_t previous = std::numeric_limits<size_t>::max();
  for (double p_th : {0.5, 0.6, 0.7}) {
    ExtrapolationOptions options;
    options.p_th = p_th;
    options.door_max_range = 10.0;  // let the kernel, not the range, bound the region
    const auto result = Extrapolate(map, entities, options);
    ASSERT_TRUE(result.ok());
    const size_t n = FreeCellsInMap(result->graph.submaps[1]).size();
    EXPECT_LT(n, previous) << p_th;
    previous = n;
  }
}

TEST(ExtrapolatorTest, OpenDoorPredictsNothing) {
  scene::Entities entities;
  entities.doors.push_back(Door());
  entities.doors[0].open = true;
  const auto result = Extrapolate(Corridor(), entities);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->graph.submaps.size(), 1u);
  EXPECT_THAT(result->graph.submaps[0].entity_ids, ::testing::Contains("door_1"));
}

TEST(ExtrapolatorTest, OpeningDirectionInferredFromTheMap) {
  scene::Entities entities;
  entities.doors.push_back(Door());
  entities.doors[0].opening_direction = Vector2::Zero();
  const auto result = Extrapolate(Corridor(), entities);
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->graph.submaps.size(), 2u);
  for (const Point2& p : FreeCellsInMap(result->graph.submaps[1])) EXPECT_GT(p.y(), 2.15);
}

TEST(ExtrapolatorTest, PersonFreeSpaceFollowsTheTrackAndExtendsForwardOnLeaving) {
  // The robot saw only x < 3 of the corridor; a person walks along y = 1 from x = 0.5 to 2.5.
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 3.0, 0.15, 10.0, 2.0, grid::kUnknownValue);
  scene::PersonTrack person;
  person.id = "p1";
  for (int i = 0; i <= 10; ++i) person.points.push_back({0.2 * i, Point2(0.5 + 0.2 * i, 1.0), 0});
  auto free_at = [](const ExtrapolationResult& r, const Point2& p) {
    const auto cell = r.conditionally_free.CellAt(p);
    return cell && r.conditionally_free.StateAt(cell->x, cell->y) == grid::CellState::kFree;
  };
  scene::Entities entities;
  entities.people.push_back(person);
  const auto stays = Extrapolate(map, entities);
  ASSERT_TRUE(stays.ok());
  EXPECT_TRUE(free_at(*stays, Point2(1.5, 1.0)));
  EXPECT_TRUE(free_at(*stays, Point2(2.5, 1.0)));
  EXPECT_FALSE(free_at(*stays, Point2(3.6, 1.0)));
  entities.people[0].left_view = true;  // 1 m/s for 0.8 s more: up to x = 3.3
  const auto leaves = Extrapolate(map, entities);
  ASSERT_TRUE(leaves.ok());
  EXPECT_TRUE(free_at(*leaves, Point2(3.6, 1.0)));
  EXPECT_FALSE(free_at(*leaves, Point2(5.0, 1.0)));
  // Never on an occupied cell, never far from the (extended) track; the observed sub-map grows.
  const grid::OccupancyGrid& cf = leaves->conditionally_free;
  int64_t claimed = 0;
  for (int y = 0; y < cf.height(); ++y) {
    for (int x = 0; x < cf.width(); ++x) {
      if (cf.StateAt(x, y) != grid::CellState::kFree) continue;
      ++claimed;
      EXPECT_NE(map.StateAt(x, y), grid::CellState::kOccupied);
      EXPECT_LT(std::abs(cf.CellCenter(x, y).y() - 1.0), 1.0);
      EXPECT_TRUE(FreeAt(leaves->graph.submaps[0], cf.CellCenter(x, y)));
    }
  }
  EXPECT_GT(claimed, 100);
}

TEST(ExtrapolatorTest, PredictedWalkStopsAtAKnownWall) {
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 3.0, 0.15, 3.15, 2.0, grid::kOccupiedValue);  // the corridor ends at x = 3
  Fill(&map, 3.15, 0.15, 10.0, 2.0, grid::kUnknownValue);
  scene::PersonTrack person;
  person.id = "p1";
  person.left_view = true;
  for (int i = 0; i <= 10; ++i) person.points.push_back({0.2 * i, Point2(0.5 + 0.2 * i, 1.0), 0});
  scene::Entities entities;
  entities.people.push_back(person);
  const auto result = Extrapolate(map, entities);
  ASSERT_TRUE(result.ok());
  const grid::OccupancyGrid& cf = result->conditionally_free;
  for (int y = 0; y < cf.height(); ++y) {
    for (int x = 0; x < cf.width(); ++x) {
      if (cf.StateAt(x, y) == grid::CellState::kFree) {
        EXPECT_LT(cf.CellCenter(x, y).x(), 3.0);
      }
    }
  }
}

TEST(ExtrapolatorTest, StairsMakeASubmapAtTheTopOnTheNextFloor) {
  scene::StairsEntity stairs;
  stairs.id = "stairs_1";
  stairs.position = Point2(6.0, 1.0);
  stairs.ascending = Vector2(1, 0);
  stairs.step_width = 1.0;
  stairs.next_floor_height = 3.0;
  stairs.run_length = 2.0;
  scene::Entities entities;
  entities.stairs.push_back(stairs);
  ExtrapolationOptions options;
  const auto result = Extrapolate(Corridor(), entities, options);
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->graph.submaps.size(), 2u);
  const scene::Submap& top = result->graph.submaps[1];
  EXPECT_EQ(top.kind, scene::SubmapKind::kPredictedStairs);
  EXPECT_DOUBLE_EQ(top.elevation, 3.0);
  EXPECT_NEAR(top.map_from_submap.x, 8.0, 1e-9);
  EXPECT_NEAR(top.map_from_submap.y, 1.0, 1e-9);
  const std::vector<Point2> free = FreeCellsInMap(top);
  ASSERT_GT(free.size(), 100u);
  const double radius =
      options.stairs_sigma_per_width * stairs.step_width * std::sqrt(2.0 * std::log(2.0));
  for (const Point2& p : free) {
    EXPECT_GT(p.x(), 8.0 + options.stairs_edge_clearance);  // beyond the top edge
    EXPECT_LE((p - Point2(8.0, 1.0)).norm(), radius + 1e-9);
  }
}

TEST(ExtrapolatorTest, UnusableEntitiesAreSkippedWithWarnings) {
  scene::Entities entities;
  entities.doors.push_back(Door());
  scene::DoorEntity zero = Door();
  zero.id = "flat";
  zero.latch = zero.hinge;
  entities.doors.push_back(zero);
  scene::PersonTrack lonely;
  lonely.id = "lonely";
  lonely.points.push_back({0.0, Point2(1, 1), 0.0});
  entities.people.push_back(lonely);
  scene::StairsEntity nan_stairs;
  nan_stairs.id = "nan";
  nan_stairs.position = Point2(std::nan(""), 0.0);
  entities.stairs.push_back(nan_stairs);
  const auto result = Extrapolate(Corridor(), entities);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->graph.submaps.size(), 2u);  // the good door
  ASSERT_EQ(result->warnings.size(), 3u);
  EXPECT_THAT(result->warnings[0], HasSubstr("person 'lonely'"));
  EXPECT_THAT(result->warnings[1], HasSubstr("door 'flat'"));
  EXPECT_THAT(result->warnings[2], HasSubstr("stairs 'nan'"));
}

TEST(ExtrapolatorTest, GarbageCoordinatesAndTrackingJumpsAreSkipped) {
  scene::Entities entities;
  scene::StairsEntity far;
  far.id = "far";
  far.position = Point2(1e300, 0.0);
  entities.stairs.push_back(far);
  scene::PersonTrack jumpy;
  jumpy.id = "jumpy";
  jumpy.points = {{0.0, Point2(1, 1), 0.0}, {0.1, Point2(1e5, 1), 0.0}};
  entities.people.push_back(jumpy);
  const auto result = Extrapolate(Corridor(), entities);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->graph.submaps.size(), 1u);
  ASSERT_EQ(result->warnings.size(), 2u);
  EXPECT_THAT(result->warnings[0], HasSubstr("person 'jumpy'"));
  EXPECT_THAT(result->warnings[0], HasSubstr("tracking error"));
  EXPECT_THAT(result->warnings[1], HasSubstr("stairs 'far'"));
}

TEST(ExtrapolatorTest, BadOptionsAndEmptyMapAreErrors) {
  ExtrapolationOptions options;
  options.p_th = 1.0;
  EXPECT_FALSE(Extrapolate(Corridor(), {}, options).ok());
  options.p_th = 0.5;
  options.door_sigma_depth_per_width = std::nan("");
  EXPECT_FALSE(Extrapolate(Corridor(), {}, options).ok());
  options.door_sigma_depth_per_width = 1.3;
  options.min_place_area = -1.0;
  EXPECT_FALSE(Extrapolate(Corridor(), {}, options).ok());
  EXPECT_FALSE(Extrapolate(grid::OccupancyGrid(), {}).ok());
}

TEST(PredictionCheckTest, CountsAgainstAnObservation) {
  scene::Submap predicted;
  predicted.map_from_submap = Pose2{1.0, 0.0, 0.0};
  predicted.navigable = grid::OccupancyGrid(4, 1, 1.0);  // cells at x = 1.5 .. 4.5 in the map
  for (int x = 0; x < 4; ++x) predicted.navigable.at(x, 0) = grid::kFreeValue;
  grid::OccupancyGrid observed(4, 1, 1.0);  // x in [0, 4)
  observed.at(1, 0) = grid::kFreeValue;
  observed.at(2, 0) = grid::kFreeValue;
  observed.at(3, 0) = grid::kOccupiedValue;
  const PredictionCheck check = CheckPrediction(predicted, observed);
  EXPECT_EQ(check.true_free, 2);
  EXPECT_EQ(check.false_free, 1);
  EXPECT_EQ(check.unobserved, 1);  // x = 4.5 is outside
  EXPECT_DOUBLE_EQ(check.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(check.observed_fraction, 0.75);
  PredictionCheck sum = check;
  sum += check;
  EXPECT_EQ(sum.true_free, 4);
  EXPECT_DOUBLE_EQ(sum.precision, 2.0 / 3.0);
}

}  // namespace
}  // namespace fleetmap::extrapolation
