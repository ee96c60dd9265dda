#pragma once

// The object-learning paper's comparison (ALGORITHMS.md 2, "The flat baseline") on simulated
// data like its second data set: objects of a few shapes in a lab, mapped in several sessions
// with the objects moved in between. Used by `fleetmap bench objects` and its tests.

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/object_learner.hpp"
#include "common/object_learning/snapshot_extractor.hpp"
#include "common/sim/mapping_sessions.hpp"

namespace fleetmap::bench {

struct ObjectDatasetOptions {
  std::string terrain = "lab";  // "lab" (LabTerrain) or "office" (TerrainGenerator)
  double size = 10.0;           // metres
  uint32_t seed = 1;            // terrain (office), plan and exploration seeds derive from it
  sim::SessionPlanOptions plan;
};

// The simulated sessions, their maps, the extracted snapshots and which true object each snapshot
// shows (-1: none within reach: a spurious snapshot).
struct ObjectDataset {
  std::vector<sim::MappedSession> sessions;
  std::vector<grid::OccupancyGrid> maps;
  object_learning::SnapshotSet snapshots;
  std::vector<int> snapshot_truth;  // true object id of each snapshot
  std::vector<int> object_class;    // true shape (class) of each object id
  int true_objects = 0;
  int true_templates = 0;
};

StatusOr<ObjectDataset> MakeObjectDataset(const ObjectDatasetOptions& options,
                                          const object_learning::SnapshotOptions& snapshots);

// A learned solution is good when (1) every learned object's snapshots (MAP assignment) show one
// shape only, (2) there are as many learned objects of each shape as true objects (two chairs:
// two chair objects) and, for the hierarchical model, (3) the MAP object -> template assignment
// groups the learned objects exactly as their shapes do. This is the true snapshot partition up
// to exchanging snapshots between objects of identical shape that never stand in the same map,
// which nothing in the data distinguishes (the simulated chairs are identical); mutual exclusion
// still forces two chairs of one map onto two objects. Spurious snapshots are not judged.
bool SamePartition(const std::vector<int>& a, const std::vector<int>& b);
bool IsGoodSolution(const ObjectDataset& data, const std::vector<int>& snapshot_object,
                    const std::vector<int>& object_template, bool hierarchical);

struct ModelComparison {
  std::string model;  // "hierarchical" or "flat"
  int starts = 0;
  int good = 0;                              // starts that reached the good solution
  std::vector<double> train_log_likelihood;  // per start, log p(data, model) at the true (N, M)
  double test_log_likelihood = 0.0;          // leave-one-map-out, summed over the held-out maps
  int chosen_objects = 0;                    // model selection's (N, M) (M = 0 for flat)
  int chosen_templates = 0;
  std::vector<object_learning::ModelScore> searched;
  double seconds_starts = 0.0;     // the random starts, all together
  double seconds_selection = 0.0;  // model selection (the learn-objects core)
  double seconds_cross_validation = 0.0;
};

struct ObjectExperimentResult {
  int maps = 0;
  int snapshots = 0;
  int spurious_snapshots = 0;
  std::vector<int> per_map;
  int true_objects = 0;
  int true_templates = 0;
  ModelComparison hierarchical;
  ModelComparison flat;
};

// `starts` single EM runs of one model at (num_objects, num_templates), from the seeds
// options.seed, options.seed + 1, ...: how many reach the good solution (IsGoodSolution), the
// training log-likelihood of each and their time together.
struct RandomStarts {
  int good = 0;
  std::vector<double> train_log_likelihood;
  double seconds = 0.0;
};
RandomStarts RunRandomStarts(const ObjectDataset& data, const object_learning::EmProblem& problem,
                             int num_objects, int num_templates, bool hierarchical, int starts,
                             const object_learning::LearnOptions& options);

// How many of `log_likelihoods` are within `tolerance` nats of the largest: the starts that
// reached an optimum as good as the best any start found (the paper's "equally good model").
int NearBest(const std::vector<double>& log_likelihoods, double tolerance);

// Leave one map out: for each map with snapshots, train on the others at (num_objects,
// num_templates) (options.restarts starts, the best kept) and score the held-out map's snapshots;
// the sum over the maps. Snapshots are extracted once from all maps (differencing needs them).
double LeaveOneMapOutLogLikelihood(const object_learning::EmProblem& problem, int num_objects,
                                   int num_templates, const object_learning::LearnOptions& options);

// The number of objects EM is run with on `data`: the true count, or more if one map shows more
// snapshots (mutual exclusion needs an object for each).
int ObjectsToLearn(const ObjectDataset& data, const object_learning::EmProblem& problem);

// Runs `starts` random starts of each model at the true (N, M), leave-one-map-out cross
// validation of each at the true (N, M), and model selection with each.
ObjectExperimentResult RunObjectExperiment(const ObjectDataset& data, int starts,
                                           const object_learning::LearnOptions& options);

}  // namespace fleetmap::bench
