#pragma once

// The entities a robot recognises and the extrapolation uses (ALGORITHMS.md 3): doors
// (quasi-static), stairs (static) and people tracks (dynamic). Plain data shared by the agent's
// detectors, the DDS edge and the server's extrapolation. Positions are in the frame of the map
// they were seen in (the robot's map frame unless ToFleetFrame moved them), metres;
// docs/extrapolation.md describes their JSON form.

#include <string>
#include <variant>
#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::scene {

// A door in a wall: its two jamb points on the floor. The hinge jamb holds the rotation axis; the
// latch jamb the handle side. `opening_direction` is the unit normal of the door line pointing
// into the side the robot has not seen (where a predicted sub-map goes when the door is closed).
struct DoorEntity {
  std::string id;
  Point2 hinge = Point2::Zero();
  Point2 latch = Point2::Zero();
  Vector2 opening_direction = Vector2::UnitY();
  bool open = false;

  double width() const { return (latch - hinge).norm(); }
  Point2 center() const { return 0.5 * (hinge + latch); }
};

// A flight of stairs going up from the robot's floor. `position` is the middle of the foot of the
// flight (the front edge of the first step, on the floor); `ascending` the unit horizontal
// direction going up; `step_width` the width of the steps across the flight (metres);
// `next_floor_height` the rise from this floor to the floor at the top. `run_length` is the
// horizontal distance from the foot to the top edge; 0 means unknown (the extrapolator then
// assumes a standard pitch, extrapolation::ExtrapolationOptions::stairs_default_pitch).
struct StairsEntity {
  std::string id;
  Point2 position = Point2::Zero();
  Vector2 ascending = Vector2::UnitX();
  double step_width = 1.0;
  double next_floor_height = 3.0;
  double run_length = 0.0;
};

// One observation of a person: time (seconds, any epoch), body centroid, torso heading (radians,
// counter-clockwise from the map's +x).
struct TrackPoint {
  double stamp = 0;
  Point2 position = Point2::Zero();
  double heading = 0;
};

// A person's observed trajectory, points in time order. `dominant_side` is -1 (left) or +1
// (right), the side the person keeps nearer to obstacles; 0 asks the extrapolator to infer it
// from the map. `left_view` / `entered_view`: the person left the sensor's view after the last
// point (the track is extended forward) / entered it before the first (extended backward).
struct PersonTrack {
  std::string id;
  std::vector<TrackPoint> points;
  int dominant_side = 0;
  bool left_view = false;
  bool entered_view = false;
};

struct Entities {
  std::vector<DoorEntity> doors;
  std::vector<StairsEntity> stairs;
  std::vector<PersonTrack> people;
};

// Any one entity, as one sample of rt/fleetmap/entities carries it.
using Entity = std::variant<DoorEntity, StairsEntity, PersonTrack>;

// The entity's own id (unique per robot).
const std::string& EntityId(const Entity& entity);

}  // namespace fleetmap::scene
