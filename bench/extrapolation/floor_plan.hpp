#pragma once

// Building floor plans drawn procedurally in the style of real floor-plan datasets (CubiCasa5k,
// R2V: drawn plans of offices and flats), for the closed-door benchmark
// (docs/extrapolation.md, "Benchmark on floor plans"): thick exterior walls (0.3-0.5 m) and
// interior walls (0.15-0.35 m), a corridor with rooms of different widths off both sides, one
// door per room onto the corridor, most hinged near a corner of the room, either face of the wall
// holding the leaf, some rooms joined to a neighbour by a second, open doorway, some shallower
// than their neighbours (the outline steps in behind them), some with a closet walled off in a
// back corner. Unlike the
// simulator's offices (common/sim: 0.12 m walls, doors anywhere), the walls are as thick as drawn
// plans and laser scans show them and the corner rooms end at the building's exterior wall, with
// nothing known outside.
//
// A plan's ground truth is its room labels. `HideRoom` makes the local map of the usual test
// case: one room behind its closed door, every other room and the corridor observed, walls seen
// only on the faces the robot could see, with a few laser dropouts in them.
//
// Thread-safety: stateless.

#include <cstdint>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {

// Cell labels besides room indices (>= 0).
inline constexpr int32_t kPlanCorridor = -1;
inline constexpr int32_t kPlanWall = -2;
inline constexpr int32_t kPlanOutside = -3;
// A real map's unknown cell (room_segmentation.hpp): nobody scanned it, so there is no ground truth
// there; hidden like outside, and a prediction on it is neither right nor wrong (unscored).
inline constexpr int32_t kPlanUnknown = -4;
// A real map's unknown cell outside the building (room_segmentation.hpp, SegmentBuilding): no scan
// there either, but no building: the strict score counts a prediction there wrong.
inline constexpr int32_t kPlanUnknownOutside = -5;

struct PlanDoor {
  // The ends of the closed leaf (map frame, metres), on one face of the wall.
  Point2 jamb_a = Point2::Zero();
  Point2 jamb_b = Point2::Zero();
  Vector2 into_room = Vector2::Zero();  // unit normal from the corridor into the room
  int32_t room = 0;
  bool leaf_on_corridor_face = true;  // else on the room's face, behind a recess
  bool end_room = false;              // the room's side wall is the building's exterior wall
  bool second_doorway = false;        // the room has an open doorway into a neighbour
  std::vector<size_t> leaf_cells;     // the cells the closed leaf covers (row-major)
};

struct FloorPlan {
  // Free on the rooms, the corridor and the doorways; occupied on walls and outside.
  grid::OccupancyGrid truth;
  std::vector<int32_t> labels;  // per cell (row-major): a room index or kPlan*
  // Per cell (row-major): 1 on an open doorway through the wall between two neighbouring rooms.
  // It is labelled one of the two rooms (the generator's coin flip), so scoring counts it for
  // neither: a prediction there is unscored and it is not in a room's recall.
  std::vector<uint8_t> between_rooms;
  std::vector<PlanDoor> doors;  // one per room, onto the corridor, in room order
  int32_t rooms = 0;
  int32_t connecting_doorways = 0;
  // Per room: 1 if the robot never went in (HideRoom leaves it unknown, its walls seen from the
  // corridor only), so the hidden room's outer wall is often not seen next to it.
  std::vector<uint8_t> unexplored;
};

struct FloorPlanOptions {
  double resolution = 0.05;
  double corner_door_probability = 0.7;         // a door whose edge is 0.05-0.3 m from a side wall
  double connecting_doorway_probability = 0.3;  // per pair of neighbouring rooms
  double shallow_room_probability = 0.3;  // a room 2 m deep or more, short of the exterior wall
  double closet_probability = 0.25;       // per room at least 3 m wide and 3.5 m deep
  // Outside space drawn around the building (metres; unknown to the robot, wrong if predicted).
  double outside_margin = 3.0;
  // Per room: the robot never went in (issue 36: rooms at the building's edge whose outer wall
  // nobody saw from inside). 0 gives the plans of issue 21 (every other room observed).
  double unexplored_room_probability = 0.3;
};

// Errors: a resolution outside [0.01, 0.2] m.
StatusOr<FloorPlan> GenerateFloorPlan(const FloorPlanOptions& options, uint32_t seed);

struct HiddenRoomScene {
  grid::OccupancyGrid local;  // the robot's map: the room behind the door unknown
  scene::DoorEntity door;     // the closed door, hinge at jamb_a (or jamb_b if swapped)
  // The closed doors of the unexplored rooms, which the robot passed and saw (hinge at jamb_a).
  std::vector<scene::DoorEntity> other_doors;
};

// The local map with `door`'s room hidden: its cells (and the unexplored rooms', whose doors are
// closed, their leaves seen from the corridor and listed in `other_doors`) unknown, the door's leaf
// occupied, walls occupied only where a cell the robot saw free touches them (8-neighbours),
// outside unknown; then, per wall face cell, with probability `dropout` a laser dropout of 1-4
// cells along the face (a gap narrower than a person). `swap_hinge` gives jamb_b as the hinge.
HiddenRoomScene HideRoom(const FloorPlan& plan, const PlanDoor& door, bool swap_hinge,
                         double dropout, sim::Random* random);

}  // namespace fleetmap::bench
