#pragma once

// Learns models of the things that move in an environment (chairs, bins, boxes) from occupancy
// maps of the same place taken at different times, and the classes (templates) they belong to:
// the hierarchical object maps of Anguelov, Biswas, Koller, Limketkai and Thrun (UAI 2002),
// ALGORITHMS.md section 2, docs/object-learning.md.
//
// Pipeline: map differencing cuts one snapshot per moved object out of every map
// (SnapshotExtractor); hierarchical EM with deterministic annealing learns objects, templates,
// correspondences and alignments for each candidate (N objects, M templates) (HierarchicalEm);
// model selection keeps the (N, M) of highest log posterior (ModelSelection).
//
// Thread-safety: LearnObjects is a pure function of its arguments; it may run concurrently.

#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/alignment.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

// Where snapshot `k` of map `map_index` went: the object it shows (MAP correspondence), the
// map-frame centre of its patch, and the alignment that maps it onto the object's patch.
struct SnapshotAssignment {
  int map_index = 0;
  int object = 0;
  Point2 centre = Point2::Zero();  // map frame, metres
  Alignment alignment;
};

// Where object `assignment.object` stood when this snapshot was taken: the map-frame pose of the
// object patch's centre and axes (yaw counter-clockwise from the map's x axis). The alignment
// moves the snapshot onto the object, theta(p) = mu(R(-dphi) (p - d)), so the object's frame sits
// at centre - R(-dphi) d, turned by -dphi.
Pose2 ObjectPoseInMap(const SnapshotAssignment& assignment);

// One point of the (N, M) grid that model selection searched.
struct ModelScore {
  int num_objects = 0;
  int num_templates = 0;
  double log_posterior = 0.0;  // log p(data, model) - c_N * N - c_M * M, nats
};

struct LearnedModel {
  int num_objects = 0;
  int num_templates = 0;
  double log_posterior = 0.0;
  std::vector<scene::Patch> templates;        // alpha_1..alpha_M
  std::vector<scene::Patch> objects;          // theta_1..theta_N
  std::vector<int> object_template;           // z_n: template of each object (MAP)
  std::vector<SnapshotAssignment> snapshots;  // every snapshot, in extraction order
  std::vector<ModelScore> searched;           // the (N, M) grid, in search order
  std::vector<std::string> warnings;          // e.g. the approximate E-step was used
  // The memory budget made the learner degrade (fewer restarts or sessions, coarser patches,
  // fewer objects searched); the warnings say how.
  bool degraded = false;
  double estimated_memory_mb = 0.0;  // the learner's estimate of its own peak (memory_plan.hpp)
};

// Learns objects and templates from `maps` (at least two, same size, resolution and origin; they
// must share a frame). A difference-free set of maps gives an empty model (N = M = 0) and a
// warning saying so. Errors (kInvalidArgument): fewer than two maps, maps whose geometry differs
// (the message names the map indices), invalid options (the message names the option).
// Memory stays within options.memory_budget_mb by degrading (never by failing); progress goes
// to options.progress.
StatusOr<LearnedModel> LearnObjects(const std::vector<grid::OccupancyGrid>& maps,
                                    const LearnOptions& options = {});

}  // namespace fleetmap::object_learning
