#pragma once

// The closed-door experiment on floor plans (floor_plan.hpp; docs/extrapolation.md, "Benchmark on
// floor plans"): in each plan, each room in turn is hidden behind its closed door, the door given
// exactly as an entity (with the true opening direction), everything else observed; the door's
// predicted sub-map is scored against the room, once with each jamb as the hinge.
//
// Scores per door, hinge choice and threshold: a predicted free cell is right only if it lies in
// the hidden room (walls, outside, other rooms and the corridor are wrong, observed or not; on a
// real map's unknown cells inside the building, where nothing says what is there, it is unscored
// and reported apart; on its unknown cells outside the building it is wrong: the strict score);
// the room's cells within `recall_radius` of the door's centre give the recall within the kernel's
// reach. `fleetmap bench extrapolation --plans N` prints and writes the totals.
//
// Thread-safety: stateless.

#include <cstdint>
#include <string>
#include <vector>

#include "bench/extrapolation/floor_plan.hpp"
#include "common/core/status.hpp"
#include "common/extrapolation/extrapolator.hpp"

namespace fleetmap::bench {

struct FloorPlanExperimentOptions {
  uint32_t seed = 1;  // one plan
  std::vector<double> p_th = {0.5, 0.6, 0.7};
  double resolution = 0.05;
  double dropout = 0.004;                    // laser dropouts per wall face cell (HideRoom)
  double recall_radius = 2.5;                // metres from the door's centre
  double unexplored_room_probability = 0.3;  // FloorPlanOptions (generated plans only)
  extrapolation::ExtrapolationOptions extrapolation;  // its p_th is replaced by each of p_th
  // If set, the first room's scene (jamb a as the hinge) is written there for `fleetmap
  // extrapolate`: local.yaml (+ .pgm), entities.json (the door) and truth.yaml (the plan).
  std::string example_dir;
};

struct PlanDoorScore {
  int64_t true_free = 0;         // predicted free, in the hidden room
  int64_t false_free = 0;        // predicted free anywhere else (strict: outside_building included)
  int64_t outside_building = 0;  // of false_free: outside the building (kPlanOutside, ...Outside)
  // Of outside_building: on a real map's unknown cells outside the segmented building
  // (kPlanUnknownOutside); the lenient score (until issue 36) left them unscored.
  int64_t unknown_outside = 0;
  int64_t unscored = 0;     // predicted free where the plan has no truth (kPlanUnknown)
  int64_t on_observed = 0;  // predicted free on a cell the local map shows free (also false)
  int64_t near_room = 0;    // the room's cells within recall_radius of the door's centre
  int64_t near_true = 0;    // of those, predicted free
};

struct PlanDoorResult {
  uint32_t plan_seed = 0;
  int32_t room = 0;
  bool swapped = false;  // jamb_b given as the hinge
  double width = 0.0;    // metres
  bool leaf_on_corridor_face = true;
  bool end_room = false;
  bool second_doorway = false;
  double cell_area = 0.0;
  std::vector<PlanDoorScore> scores;  // one per p_th
};

// Every room of plan `seed`, each hinge choice. Errors: bad options.
StatusOr<std::vector<PlanDoorResult>> RunFloorPlanExperiment(
    const FloorPlanExperimentOptions& options);

// Every door of `plan` (generated, or made from a real map: room_segmentation.hpp), each hinge
// choice, scored as above; `options.seed` seeds the laser dropouts and names the plan in the
// results. Errors: bad options.
StatusOr<std::vector<PlanDoorResult>> RunHiddenRoomExperiment(
    const FloorPlan& plan, const FloorPlanExperimentOptions& options);

}  // namespace fleetmap::bench
