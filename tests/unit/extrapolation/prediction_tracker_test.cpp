#include "common/extrapolation/prediction_tracker.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "tests/unit/extrapolation/test_maps.hpp"

namespace fleetmap::extrapolation {
namespace {

using testing::Corridor;
using testing::CorridorWithRooms;
using testing::DoorAt;
using ::testing::ElementsAre;
using testing::Fill;
using ::testing::IsEmpty;
using ::testing::UnorderedElementsAre;

const Timestamp kNow = Timestamp(std::chrono::seconds(1700000000));

// The corridor once another robot has mapped the room behind the door (y in [2.15, 6]): empty,
// or full of shelves.
grid::OccupancyGrid CorridorWithRoomBehind(bool shelves) {
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 0, 2.15, 10, 6.0, shelves ? grid::kOccupiedValue : grid::kFreeValue);
  Fill(&map, 0, 6.0, 10, 6.15, grid::kOccupiedValue);
  return map;
}

// Robot alpha's door_1 in the corridor's upper wall (closed: Corridor()'s door).
scene::DoorEntity Door(bool open = false, double hinge_x = 4.0) {
  return DoorAt("door_1", hinge_x, hinge_x + 1.0, 2.075, open);
}

TrackerInput From(const std::string& robot, scene::Entity entity) {
  return RobotEntity{RobotId{robot}, kNow, std::move(entity)};
}

PredictionTracker MakeTracker(PredictionOptions options = {}) {
  StatusOr<PredictionTracker> tracker = PredictionTracker::Create(options);
  EXPECT_TRUE(tracker.ok()) << tracker.status();
  return std::move(tracker).value();
}

// Hands the tracker one batch.
TrackerUpdate Handle(PredictionTracker& tracker, std::vector<TrackerInput> inputs) {
  return tracker.Handle(std::move(inputs), kNow);
}

// The nodes written with ids from kFirstPredictedSubmap (predictions, not places).
std::vector<scene::SubmapNode> PredictionsWritten(const TrackerUpdate& update) {
  std::vector<scene::SubmapNode> out;
  for (const SubmapChange& change : update.changes) {
    if (change.kind == SubmapChange::Kind::kWrite &&
        change.node.submap.id >= kFirstPredictedSubmap) {
      out.push_back(change.node);
    }
  }
  return out;
}

std::vector<uint32_t> Withdrawn(const TrackerUpdate& update) {
  std::vector<uint32_t> out;
  for (const SubmapChange& change : update.changes) {
    if (change.kind == SubmapChange::Kind::kWithdraw) out.push_back(change.node.submap.id);
  }
  return out;
}

std::vector<scene::SubmapNode> PlacesWritten(const TrackerUpdate& update) {
  std::vector<scene::SubmapNode> out;
  for (const SubmapChange& change : update.changes) {
    if (change.kind == SubmapChange::Kind::kWrite &&
        change.node.submap.id < kFirstPredictedSubmap) {
      out.push_back(change.node);
    }
  }
  return out;
}

std::vector<uint32_t> EdgeTargets(const scene::SubmapNode& node) {
  std::vector<uint32_t> out;
  for (const scene::SubmapEdge& edge : node.edges) out.push_back(edge.to);
  return out;
}

// The value of a place's cell at a fleet-frame point (places share the fleet frame).
std::optional<int8_t> CellAt(const scene::SubmapNode& place, const Point2& point) {
  const auto cell = place.submap.navigable.CellAt(point);
  if (!cell) return std::nullopt;
  return place.submap.navigable.at(cell->x, cell->y);
}

TEST(PredictionTrackerTest, RefusesInvalidOptions) {
  PredictionOptions options;
  options.confirm_precision = 1.5;
  EXPECT_FALSE(PredictionTracker::Create(options).ok());
  options = {};
  options.min_observed_cells = 0;
  EXPECT_FALSE(PredictionTracker::Create(options).ok());
}

TEST(PredictionTrackerTest, PredictsBehindAClosedDoorOnceTheMapArrives) {
  PredictionTracker tracker = MakeTracker();
  // An entity before any fused grid waits for one.
  EXPECT_THAT(Handle(tracker, {From("alpha", Door())}).changes, IsEmpty());
  EXPECT_EQ(tracker.stats().entities, 1u);
  EXPECT_EQ(tracker.stats().predictions, 0u);

  const TrackerUpdate update = Handle(tracker, {Corridor()});
  const std::vector<scene::SubmapNode> predicted = PredictionsWritten(update);
  ASSERT_EQ(predicted.size(), 1u);
  const scene::SubmapNode& node = predicted[0];
  EXPECT_EQ(node.submap.id, kFirstPredictedSubmap);
  EXPECT_EQ(node.submap.place, kFirstPredictedSubmap);
  EXPECT_EQ(node.submap.kind, scene::SubmapKind::kPredictedDoor);
  EXPECT_EQ(node.state, scene::SubmapState::kPredicted);
  EXPECT_EQ(node.source_robot.value, "alpha");
  EXPECT_EQ(node.source_entity, "door_1");
  EXPECT_EQ(node.precision, -1.0F);
  EXPECT_TRUE(node.submap.confidence.empty());  // the wire carries thresholded cells only
  EXPECT_GT(node.submap.navigable.CountStates().free, 100);
  EXPECT_EQ(node.stamp, kNow);
  // Joined to the corridor, the place the door opens from; the corridor points back.
  EXPECT_THAT(EdgeTargets(node), ElementsAre(0u));
  EXPECT_EQ(node.edges[0].entity_id, "door_1");
  const std::vector<scene::SubmapNode> places = PlacesWritten(update);
  ASSERT_EQ(places.size(), 1u);
  EXPECT_EQ(places[0].state, scene::SubmapState::kObserved);
  EXPECT_THAT(EdgeTargets(places[0]), ElementsAre(kFirstPredictedSubmap));
  EXPECT_EQ(tracker.stats().predictions, 1u);
  EXPECT_EQ(tracker.stats().places, 1u);
}

TEST(PredictionTrackerTest, AnIdenticalEntitySentAgainChangesNothing) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  // Robots re-send their entities: the prediction being checked is not made again.
  EXPECT_THAT(Handle(tracker, {From("alpha", Door())}).changes, IsEmpty());
  EXPECT_THAT(Handle(tracker, {From("alpha", Door()), From("alpha", Door())}).changes, IsEmpty());
  // Nor by the same fused grid again.
  EXPECT_THAT(Handle(tracker, {Corridor()}).changes, IsEmpty());
  EXPECT_EQ(tracker.stats().predictions, 1u);
}

TEST(PredictionTrackerTest, AResentEntityDoesNotResetWhatWasMeasured) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  // A robot maps a strip of the room behind the door: too little to judge, but measured.
  grid::OccupancyGrid strip = Corridor();
  Fill(&strip, 3.5, 2.15, 5.5, 2.6, grid::kFreeValue);
  const std::vector<scene::SubmapNode> measured = PredictionsWritten(Handle(tracker, {strip}));
  ASSERT_EQ(measured.size(), 1u);
  EXPECT_EQ(measured[0].state, scene::SubmapState::kPredicted);
  EXPECT_GT(measured[0].precision, 0.9F);
  EXPECT_GT(measured[0].observed_fraction, 0.0F);
  EXPECT_LT(measured[0].observed_fraction, 0.5F);

  EXPECT_THAT(Handle(tracker, {From("alpha", Door())}).changes, IsEmpty());
  // The room observed in full judges the same prediction: it was never made again.
  const std::vector<scene::SubmapNode> judged =
      PredictionsWritten(Handle(tracker, {CorridorWithRoomBehind(false)}));
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_EQ(judged[0].state, scene::SubmapState::kConfirmed);
}

TEST(PredictionTrackerTest, AChangedEntityIsPredictedAgainUnderTheSameId) {
  PredictionTracker tracker = MakeTracker();
  const std::vector<scene::SubmapNode> first =
      PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())}));
  ASSERT_EQ(first.size(), 1u);
  // The robot sees the door 20 cm further along: a new prediction, the same sub-map id.
  const TrackerUpdate moved = Handle(tracker, {From("alpha", Door(false, 4.2))});
  const std::vector<scene::SubmapNode> again = PredictionsWritten(moved);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].submap.id, first[0].submap.id);
  // Made against the moved door: its frame sits 20 cm further along.
  EXPECT_NEAR(again[0].submap.map_from_submap.x - first[0].submap.map_from_submap.x, 0.2, 1e-9);
  EXPECT_THAT(Withdrawn(moved), IsEmpty());
  // Another robot's door of the same name is another prediction.
  const std::vector<scene::SubmapNode> other =
      PredictionsWritten(Handle(tracker, {From("beta", Door())}));
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(other[0].submap.id, kFirstPredictedSubmap + 1);
  EXPECT_EQ(other[0].source_robot.value, "beta");
  EXPECT_EQ(tracker.stats().predictions, 2u);
}

TEST(PredictionTrackerTest, AnOpenedDoorWithdrawsItsPredictionAndAClosedOneBringsItBack) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  const TrackerUpdate opened = Handle(tracker, {From("alpha", Door(/*open=*/true))});
  EXPECT_THAT(Withdrawn(opened), ElementsAre(kFirstPredictedSubmap));
  EXPECT_THAT(PredictionsWritten(opened), IsEmpty());
  EXPECT_EQ(tracker.stats().predictions, 0u);
  EXPECT_EQ(tracker.stats().entities, 1u);
  // Shut again: predicted again, under the id it had.
  const std::vector<scene::SubmapNode> closed =
      PredictionsWritten(Handle(tracker, {From("alpha", Door())}));
  ASSERT_EQ(closed.size(), 1u);
  EXPECT_EQ(closed[0].submap.id, kFirstPredictedSubmap);
  EXPECT_EQ(closed[0].state, scene::SubmapState::kPredicted);
}

TEST(PredictionTrackerTest, ARemovedEntityTakesItsPredictionAndThePlacesWithIt) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  // Only the owner's removal counts: beta has no door_1.
  EXPECT_THAT(Handle(tracker, {EntityRemoval{RobotId{"beta"}, "door_1"}}).changes, IsEmpty());
  const TrackerUpdate removed = Handle(tracker, {EntityRemoval{RobotId{"alpha"}, "door_1"}});
  // The prediction, then the one place: with no entity the place would be the fused map again.
  EXPECT_THAT(Withdrawn(removed), ElementsAre(kFirstPredictedSubmap, 0u));
  EXPECT_EQ(tracker.stats().entities, 0u);
  EXPECT_EQ(tracker.stats().predictions, 0u);
  EXPECT_EQ(tracker.stats().places, 0u);
}

TEST(PredictionTrackerTest, ConfirmsWhatLaterObservationFindsFree) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  const std::vector<scene::SubmapNode> judged =
      PredictionsWritten(Handle(tracker, {CorridorWithRoomBehind(false)}));
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_EQ(judged[0].state, scene::SubmapState::kConfirmed);
  EXPECT_GE(judged[0].precision, 0.9F);
  EXPECT_GE(judged[0].observed_fraction, 0.5F);
  EXPECT_EQ(tracker.stats().confirmed, 1u);
  EXPECT_EQ(tracker.stats().retracted, 0u);
  // Judged once: later maps leave it alone.
  grid::OccupancyGrid later = CorridorWithRoomBehind(false);
  Fill(&later, 3.0, 2.5, 6.0, 3.5, grid::kOccupiedValue);
  EXPECT_THAT(PredictionsWritten(Handle(tracker, {later})), IsEmpty());
  EXPECT_EQ(tracker.stats().confirmed, 1u);
}

TEST(PredictionTrackerTest, RetractsWhatLaterObservationContradicts) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  // Two grids in one batch: only the newest counts.
  const std::vector<scene::SubmapNode> judged = PredictionsWritten(
      Handle(tracker, {CorridorWithRoomBehind(false), CorridorWithRoomBehind(true)}));
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_EQ(judged[0].state, scene::SubmapState::kRetracted);
  EXPECT_LT(judged[0].precision, 0.1F);
  EXPECT_EQ(tracker.stats().retracted, 1u);
  EXPECT_EQ(tracker.stats().confirmed, 0u);
}

TEST(PredictionTrackerTest, APredictionUpTheStairsStaysPredicted) {
  PredictionTracker tracker = MakeTracker();
  const scene::StairsEntity stairs{.id = "stairs_1",
                                   .position = Point2(8.0, 1.0),
                                   .ascending = Vector2(1, 0),
                                   .step_width = 1.4,
                                   .next_floor_height = 3.0,
                                   .run_length = 1.5};
  const std::vector<scene::SubmapNode> predicted =
      PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", stairs)}));
  ASSERT_EQ(predicted.size(), 1u);
  EXPECT_EQ(predicted[0].submap.kind, scene::SubmapKind::kPredictedStairs);
  EXPECT_GT(predicted[0].submap.elevation, 0.0);
  // The fused map is one floor: whatever it shows there says nothing of the floor above.
  grid::OccupancyGrid seen = Corridor();
  Fill(&seen, 0, 0, 10, 8, grid::kOccupiedValue);
  EXPECT_THAT(PredictionsWritten(Handle(tracker, {seen})), IsEmpty());
  EXPECT_EQ(tracker.stats().retracted, 0u);
}

TEST(PredictionTrackerTest, SplitsTheFusedMapIntoPlacesAtDoors) {
  // Two rooms above the corridor, split by a wall at x = 4.9, each seen through an open door.
  const grid::OccupancyGrid map = CorridorWithRooms();
  PredictionTracker tracker = MakeTracker();
  const TrackerUpdate update =
      Handle(tracker, {map, From("alpha", DoorAt("door_a", 2.0, 3.0, 2.075, /*open=*/true)),
                       From("alpha", DoorAt("door_b", 6.0, 7.0, 2.075, /*open=*/true))});
  EXPECT_THAT(PredictionsWritten(update), IsEmpty());  // open doors predict nothing
  const std::vector<scene::SubmapNode> places = PlacesWritten(update);
  ASSERT_EQ(places.size(), 3u);
  // The corridor (place 0) reaches both rooms through the doors; each room only the corridor.
  EXPECT_THAT(EdgeTargets(places[0]), UnorderedElementsAre(1u, 2u));
  EXPECT_THAT(EdgeTargets(places[1]), ElementsAre(0u));
  EXPECT_THAT(EdgeTargets(places[2]), ElementsAre(0u));
  for (const scene::SubmapNode& place : places) {
    EXPECT_EQ(place.state, scene::SubmapState::kObserved);
    for (const scene::SubmapEdge& edge : place.edges) {
      EXPECT_EQ(edge.from, place.submap.id);  // edges start at their node
    }
  }
  EXPECT_EQ(CellAt(places[0], Point2(5.0, 1.0)), grid::kFreeValue);
  EXPECT_EQ(CellAt(places[1], Point2(3.0, 4.0)), grid::kFreeValue);
  EXPECT_NE(CellAt(places[0], Point2(3.0, 4.0)), grid::kFreeValue);
  EXPECT_EQ(tracker.stats().places, 3u);
  // Only what changed goes out again.
  EXPECT_THAT(Handle(tracker, {map}).changes, IsEmpty());
}

TEST(PredictionTrackerTest, MarksConditionallyFreeCellsAlongAPersonsTrack) {
  // The robots saw only x < 3 of the corridor; a person walks along y = 1 from x = 0.5 to 2.5
  // and leaves the view: the track goes on to about x = 3.3, through space nobody mapped.
  grid::OccupancyGrid map = Corridor();
  Fill(&map, 3.0, 0.15, 10.0, 2.0, grid::kUnknownValue);
  scene::PersonTrack person;
  person.id = "person_1";
  person.left_view = true;
  for (int i = 0; i <= 10; ++i) person.points.push_back({0.2 * i, Point2(0.5 + 0.2 * i, 1.0), 0});
  PredictionTracker tracker = MakeTracker();
  const TrackerUpdate update = Handle(tracker, {map, From("alpha", person)});
  EXPECT_THAT(PredictionsWritten(update), IsEmpty());  // people enlarge a place, predict none
  const std::vector<scene::SubmapNode> places = PlacesWritten(update);
  ASSERT_EQ(places.size(), 1u);
  const scene::SubmapNode& place = places[0];
  EXPECT_THAT(place.submap.entity_ids, ::testing::Contains("alpha/person_1"));
  // Mapped free stays free; free only because the person walked there is marked as such.
  EXPECT_EQ(CellAt(place, Point2(1.5, 1.0)), grid::kFreeValue);
  EXPECT_EQ(CellAt(place, Point2(3.2, 1.0)), kConditionallyFree);
  EXPECT_NE(CellAt(place, Point2(5.0, 1.0)), kConditionallyFree);
  int64_t marked = 0;
  for (const int8_t value : place.submap.navigable.data()) marked += value == kConditionallyFree;
  EXPECT_GT(marked, 20);
  // The person's track changes: the place goes out again; the same track again changes nothing.
  person.left_view = false;
  EXPECT_EQ(PlacesWritten(Handle(tracker, {From("alpha", person)})).size(), 1u);
  EXPECT_THAT(Handle(tracker, {From("alpha", person)}).changes, IsEmpty());
}

TEST(PredictionTrackerTest, AnIdReusedForAnotherKindOfEntityWithdrawsItsPrediction) {
  PredictionTracker tracker = MakeTracker();
  ASSERT_EQ(PredictionsWritten(Handle(tracker, {Corridor(), From("alpha", Door())})).size(), 1u);
  scene::PersonTrack person;
  person.id = "door_1";
  for (int i = 0; i <= 10; ++i) person.points.push_back({0.2 * i, Point2(0.5 + 0.2 * i, 1.0), 0});
  const TrackerUpdate update = Handle(tracker, {From("alpha", person)});
  EXPECT_THAT(Withdrawn(update), ElementsAre(kFirstPredictedSubmap));
  EXPECT_EQ(tracker.stats().predictions, 0u);
}

}  // namespace
}  // namespace fleetmap::extrapolation
