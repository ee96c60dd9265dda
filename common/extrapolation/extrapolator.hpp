#pragma once

// Map extrapolation (ALGORITHMS.md 3, eq. 1-5): from a robot's local occupancy grid and the
// entities it recognised, builds the sub-map graph: one observed sub-map per topological place
// (the local map's free space, augmented with the free space people's tracks imply, cut at doors
// and at the foot of stairs: PartitionPlaces), one predicted sub-map behind each closed door and
// one at the top of each flight of stairs, each joined to the observed sub-map it opens from.
//
// Sub-map ids: the observed sub-maps first (0 .. K-1, K >= 1, in PartitionPlaces' order), then
// the predicted ones in entity order (doors, then stairs). Edges, per door then per stairs in
// entity order: observed-to-observed through it (if its two sides are different places; lower id
// first, identity transform), then observed-to-predicted.
//
// Kernels are thresholded after normalising each to a peak of 1 (a confidence in [0, 1]), so
// p_th means the same thing whatever sigma is (docs/extrapolation.md). Predicted free space never
// claims a cell the local map shows occupied, and is clipped: doors' predictions spread only
// through cells the local map does not know (never onto observed free space, which is another
// place), off the assumed thickness of seen walls and the continuations of seen walls, through
// passages wider than a person (DoorSpace), 4-connected from the doorway, on the unseen side of
// the door and within `door_max_range`; stairs'
// predictions cover only the half-plane beyond the top of the flight; people's only cells in line
// of sight of the person (through the local map).
//
// Thread-safety: stateless; safe to call concurrently.

#include <string>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::extrapolation {

struct ExtrapolationOptions {
  // Free where the peak-normalised kernel exceeds p_th, in (0, 1).
  double p_th = 0.5;

  // Stairs: f_s = N(0, sigma^2 I) at the top of the flight, sigma = stairs_sigma_per_width * w.
  double stairs_sigma_per_width = 0.6;
  // No cell closer than this to the top edge is predicted (metres): the edge's position rests on
  // the assumed floor height (0.1 m of height moves it 0.16 m at 32 degrees).
  double stairs_edge_clearance = 0.3;
  // Pitch assumed when a stairs entity gives no run length (radians; 32 deg ~ 17 cm / 28 cm).
  double stairs_default_pitch = 0.5585;

  // Doors: f_d = 2 phi(u) Phi(alpha^T omega^-1 u) at the doorway's centre (the paper centres it on
  // the hinge; a hinge beside the room's side wall then puts half the kernel past that wall),
  // u = (along the door, into the unseen side), Omega = diag(sigma_along^2, sigma_depth^2) with
  // sigma_along = door_sigma_along_per_width * w and sigma_depth = door_sigma_depth_per_width * w,
  // alpha = (0, door_skew_per_width * w) (w in metres): the paper's isotropic Omega = sigma^2 I by
  // default; the clipping, not a narrow kernel, keeps it out of neighbouring rooms.
  double door_sigma_along_per_width = 1.3;
  double door_sigma_depth_per_width = 1.3;
  double door_skew_per_width = 3.0;
  // No cell closer than this to the door line is predicted (metres): the rest of the wall the
  // door sits in, which the robot saw from one side only.
  double door_wall_clearance = 0.15;
  // The predicted sub-map's frame sits this far behind the door's centre (the paper's d).
  double door_submap_distance = 1.0;
  // No predicted cell further than this from the door's centre (metres).
  double door_max_range = 2.5;
  // Clipping by what the map shows (DoorSpace, docs/extrapolation.md): unknown cells this far
  // behind a seen wall face are wall (metres); passages and gaps in seen faces narrower than
  // door_min_passage_width lead nowhere; seen faces at least door_min_continued_wall long are
  // continued through unknown space unless observed free space lies within door_continuation_gap
  // of their end.
  double door_unseen_wall_thickness = 0.3;
  double door_min_passage_width = 0.5;
  double door_min_continued_wall = 0.6;
  double door_continuation_gap = 0.6;
  // The building's outline (BuildingOutline, docs/extrapolation.md): a prediction never crosses
  // the continuation of an observed outer wall (a seen face at least door_min_outer_wall long,
  // metres, with no observed free space behind it) nor lands beyond the outermost one.
  bool door_building_outline = true;
  double door_min_outer_wall = 1.0;
  // Another closed door in the same wall, opening to the same side, leads to another room: a
  // door's prediction stops, along the wall, door_next_room_clearance (metres) short of the other
  // doorway's near jamb, where the room can first end (the other door's frame and the thinnest
  // interior wall, 0.05 + 0.15 m, stand between the doorway and this room).
  bool door_split_between_doors = true;
  double door_next_room_clearance = 0.2;

  // People: a skew-normal personal-space kernel in the person's frame (x forward, y left):
  // sigma_forward / sigma_side (metres), skew alpha = (person_skew_forward,
  // dominant_side * person_skew_side): more space ahead and away from the dominant side.
  double person_sigma_forward = 0.35;
  double person_sigma_side = 0.35;
  double person_skew_forward = 2.0;
  double person_skew_side = 1.0;
  // Linear prediction horizon when a person leaves / enters the view (seconds), and the spacing
  // of the poses the kernel is swept over (metres).
  double track_horizon = 0.8;
  double track_sample_spacing = 0.1;
  // Where the dominant side is inferred, obstacles are searched up to this far sideways (metres).
  double dominant_side_search = 2.0;

  // Places (docs/extrapolation.md): a part of the observed map cut off by doors and stairs is a
  // place of its own only if it has at least this area (m2, about a desk's footprint); smaller
  // parts (speckle, a corner cut off by a jamb) join the nearest place.
  double min_place_area = 0.5;

  // Cells of the grid a predicted sub-map may have at most (a bad entity must not allocate the
  // world): larger kernels are cut to this size.
  int max_submap_cells_side = 2000;

  // Errors (kInvalidArgument): p_th outside (0, 1), a non-positive or non-finite parameter.
  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

struct ExtrapolationResult {
  scene::SubmapGraph graph;
  // The free space people's tracks imply (0 where conditionally free, -1 elsewhere), with the
  // local map's geometry. These cells are also free in the observed sub-maps of the places they
  // fall in (U' = U + U_i).
  grid::OccupancyGrid conditionally_free;
  // Entities skipped or adjusted (an unusable door or track, an inferred dominant side...),
  // each naming the entity.
  std::vector<std::string> warnings;
};

// Errors (kInvalidArgument): bad options, an empty local map. Unusable entities are skipped with
// a warning, never an error.
StatusOr<ExtrapolationResult> Extrapolate(const grid::OccupancyGrid& local_map,
                                          const scene::Entities& entities,
                                          const ExtrapolationOptions& options = {});

}  // namespace fleetmap::extrapolation
