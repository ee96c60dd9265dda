#pragma once

// The sub-map graph G = {V, E} of ALGORITHMS.md 3: observed sub-maps (what the robot mapped) and
// predicted ones (behind closed doors, at the top of stairs), joined by edges that hold the
// relative transform between two sub-maps. Sub-maps not separated by a door or stairs share a
// topological place: the observed map is cut into places at doors and at the foot of stairs, one
// observed sub-map per place; a predicted sub-map is always in a place of its own.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::scene {

enum class SubmapKind : uint8_t { kObserved, kPredictedStairs, kPredictedDoor };

// "observed", "predicted_stairs", "predicted_door".
std::string_view SubmapKindName(SubmapKind kind);

// One node of the graph: S = {P, R, U} with U as a grid. `navigable`'s origin is expressed in
// the sub-map's own frame (map_from_submap * cell centre is the cell's map-frame point); free (0)
// cells are navigable, 100 occupied, -1 unknown. For a predicted sub-map, `confidence` holds the
// peak-normalised kernel value in [0, 1] per cell (row-major, same layout as `navigable`; empty
// for observed sub-maps); a cell is free where confidence > p_th and nothing known contradicts it.
// An observed sub-map's frame is the local map's (map_from_submap = identity); its grid is the
// local map's lattice cut to its place's bounding box plus one cell: free on the place's cells,
// occupied where the local map is, unknown elsewhere (including other places' free cells).
struct Submap {
  uint32_t id = 0;
  SubmapKind kind = SubmapKind::kObserved;
  uint32_t place = 0;
  Pose2 map_from_submap;
  // Height of the sub-map's floor above the local map's floor (metres): > 0 at the top of stairs.
  double elevation = 0.0;
  grid::OccupancyGrid navigable;
  std::vector<float> confidence;
  std::vector<std::string> entity_ids;  // the entities that made or augmented this sub-map
};

// An edge: `from_T_to` is the pose of sub-map `to`'s frame in sub-map `from`'s frame
// (from_T_to = inverse(map_from_from) * map_from_to).
struct SubmapEdge {
  uint32_t from = 0;
  uint32_t to = 0;
  Pose2 from_T_to;
  std::string entity_id;  // the door or stairs the edge goes through
};

struct SubmapGraph {
  std::vector<Submap> submaps;
  std::vector<SubmapEdge> edges;

  // The sub-map with this id, or nullptr.
  const Submap* Find(uint32_t id) const;
};

// from_T_to of two sub-map poses in the map frame.
Pose2 RelativePose(const Pose2& map_from_from, const Pose2& map_from_to);

// Where a sub-map stands in the fleet: observed by the robots, predicted, or a prediction that
// robots have since observed and found right (confirmed) or wrong (retracted).
enum class SubmapState : uint8_t { kObserved = 0, kPredicted = 1, kConfirmed = 2, kRetracted = 3 };

// "observed", "predicted", "confirmed", "retracted".
const char* SubmapStateName(SubmapState state);

}  // namespace fleetmap::scene
