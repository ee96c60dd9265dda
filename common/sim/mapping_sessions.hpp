#pragma once

// Mapping sessions with movable objects (issue 6): the same terrain mapped several times by the
// exploring robot while chairs, bins and boxes come, go and move in between, as the data for
// object learning (common/object_learning). PlanSessions decides which objects stand where in
// each session; MapSessions rasterizes each session's truth and explores it with
// ExplorationSimulator (by default without SLAM error, so that the maps share one frame; the
// laser's range noise, speckle and occlusions stay, so snapshots are noisy and partial).
//
// Deterministic: the same inputs (seeds included) give the same plans and map bytes.
// Thread-safety: stateless.

#include <cstdint>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/exploration_simulator.hpp"
#include "common/sim/movable_objects.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

struct SessionPlanOptions {
  // One entry per physical object (its id is its index). The default is the paper's second data
  // set: 4 objects of 3 shapes.
  std::vector<MovableShape> shapes = {MovableShape::kChair, MovableShape::kChair,
                                      MovableShape::kBin, MovableShape::kBox};
  int sessions = 9;                 // >= 2
  int min_present = 2;              // objects in each session, in [1, max_present]
  int max_present = 3;              // <= number of objects
  int min_sessions_per_object = 2;  // every object is seen at least this often, >= 1
  double clearance = 1.0;           // metres of free space between an object and walls or objects
  double start_clearance = 1.0;     // metres between an object and the robot's start
  uint32_t seed = 0;
};

// Objects of each session (present objects only), at random free poses of `truth` (a grid
// without objects). Errors (kInvalidArgument): bad options, or no room for the objects.
StatusOr<std::vector<std::vector<MovableObject>>> PlanSessions(const grid::OccupancyGrid& truth,
                                                               const Pose2& start,
                                                               const SessionPlanOptions& options);

struct MappingSessionOptions {
  ExplorationOptions exploration = DefaultExploration();  // seed + session index per session
  double resolution = 0.05;                               // metres per cell of truth and maps

  // The simulator's defaults with the SLAM error off (the maps must share a frame).
  static ExplorationOptions DefaultExploration();
};

struct MappedSession {
  std::vector<MovableObject> objects;
  grid::OccupancyGrid truth;  // terrain plus this session's objects
  grid::OccupancyGrid map;    // what the robot mapped
};

// Errors: those of RasterizeTerrain, ExplorationSimulator::Create and Run.
StatusOr<std::vector<MappedSession>> MapSessions(
    const Terrain& base, const std::vector<std::vector<MovableObject>>& plan,
    const MappingSessionOptions& options);

// A lab like the paper's second data set: a square room of side `size` metres (boundary wall),
// two static cabinets along the walls, the robot starting near a corner.
Terrain LabTerrain(double size);

}  // namespace fleetmap::sim
