#include "bench/objects/object_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/held_out_likelihood.hpp"
#include "common/object_learning/model_selection.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::bench {
namespace {

namespace ol = object_learning;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The problem without map `held_out`'s snapshots (its map keeps an empty slot).
ol::EmProblem WithoutMap(const ol::EmProblem& problem, int held_out) {
  ol::EmProblem out;
  out.maps.resize(problem.maps.size());
  for (size_t t = 0; t < problem.maps.size(); ++t) {
    if (static_cast<int>(t) == held_out) continue;
    for (int s : problem.maps[t]) {
      out.maps[t].push_back(static_cast<int>(out.snapshots.size()));
      out.snapshots.push_back(problem.snapshots[s]);
    }
  }
  return out;
}

}  // namespace

StatusOr<ObjectDataset> MakeObjectDataset(const ObjectDatasetOptions& options,
                                          const ol::SnapshotOptions& snapshot_options) {
  sim::Terrain terrain;
  if (options.terrain == "lab") {
    if (!(options.size >= 4.0 && options.size <= 100.0)) {
      return InvalidArgumentError("--size for the lab must be in [4, 100] m");
    }
    terrain = sim::LabTerrain(options.size);
  } else if (options.terrain == "office") {
    sim::TerrainOptions terrain_options;
    terrain_options.kind = sim::TerrainKind::kOffice;
    terrain_options.size = options.size;
    terrain_options.seed = options.seed;
    FLEETMAP_ASSIGN_OR_RETURN(const sim::TerrainGenerator generator,
                              sim::TerrainGenerator::Create(terrain_options));
    terrain = generator.Generate();
  } else {
    return InvalidArgumentError("--terrain '" + options.terrain + "' is unknown: lab or office");
  }
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid empty_truth,
                            sim::RasterizeTerrain(terrain, 0.05));
  sim::SessionPlanOptions plan_options = options.plan;
  plan_options.seed = options.seed;
  FLEETMAP_ASSIGN_OR_RETURN(const auto plan,
                            sim::PlanSessions(empty_truth, terrain.start, plan_options));
  sim::MappingSessionOptions mapping;
  mapping.exploration.seed = options.seed * 1000u;
  ObjectDataset data;
  FLEETMAP_ASSIGN_OR_RETURN(data.sessions, sim::MapSessions(terrain, plan, mapping));
  for (const sim::MappedSession& session : data.sessions) data.maps.push_back(session.map);
  FLEETMAP_ASSIGN_OR_RETURN(data.snapshots, ol::ExtractSnapshots(data.maps, snapshot_options));
  for (const sim::MovableShape shape : options.plan.shapes) {
    data.object_class.push_back(static_cast<int>(shape));
  }
  data.true_objects = static_cast<int>(options.plan.shapes.size());
  std::map<int, int> classes;
  for (int c : data.object_class) classes[c] = 1;
  data.true_templates = static_cast<int>(classes.size());
  for (const ol::Snapshot& snapshot : data.snapshots.snapshots) {
    int truth = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (const sim::MovableObject& object : data.sessions[snapshot.map_index].objects) {
      const double d = (object.pose.translation() - snapshot.centre).norm();
      if (d < sim::MovableShapeRadius(object.shape) + 0.25 && d < nearest) {
        nearest = d;
        truth = object.id;
      }
    }
    data.snapshot_truth.push_back(truth);
  }
  return data;
}

bool SamePartition(const std::vector<int>& a, const std::vector<int>& b) {
  if (a.size() != b.size()) return false;
  std::map<int, int> a_to_b, b_to_a;
  for (size_t i = 0; i < a.size(); ++i) {
    const auto [ia, inserted_a] = a_to_b.emplace(a[i], b[i]);
    const auto [ib, inserted_b] = b_to_a.emplace(b[i], a[i]);
    if (ia->second != b[i] || ib->second != a[i]) return false;
  }
  return true;
}

bool IsGoodSolution(const ObjectDataset& data, const std::vector<int>& snapshot_object,
                    const std::vector<int>& object_template, bool hierarchical) {
  // The class (shape) of each learned object that holds a snapshot; it must hold one class only.
  std::map<int, int> object_class;
  for (size_t s = 0; s < data.snapshot_truth.size(); ++s) {
    if (data.snapshot_truth[s] < 0) continue;  // spurious snapshots are not judged
    const int true_class = data.object_class[data.snapshot_truth[s]];
    const auto [it, inserted] = object_class.emplace(snapshot_object[s], true_class);
    if (it->second != true_class) return false;
  }
  // As many learned objects of each class as there are true objects of it.
  std::map<int, int> learned_count, true_count;
  for (const auto& [object, c] : object_class) ++learned_count[c];
  for (int c : data.object_class) ++true_count[c];
  if (learned_count != true_count) return false;
  if (!hierarchical) return true;
  // The templates group the learned objects as the classes do.
  std::vector<int> classes, templates;
  for (const auto& [object, c] : object_class) {
    classes.push_back(c);
    templates.push_back(object_template[object]);
  }
  return SamePartition(classes, templates);
}

RandomStarts RunRandomStarts(const ObjectDataset& data, const ol::EmProblem& problem,
                             int num_objects, int num_templates, bool hierarchical, int starts,
                             const ol::LearnOptions& options) {
  RandomStarts result;
  const auto start_time = std::chrono::steady_clock::now();
  ol::LearnOptions single = options;
  single.hierarchical = hierarchical;
  single.restarts = 1;
  for (int i = 0; i < starts; ++i) {
    single.seed = options.seed + static_cast<uint32_t>(i);
    const ol::EmResult run = ol::BestOfRestarts(problem, num_objects, num_templates, single);
    result.train_log_likelihood.push_back(run.log_likelihood);
    result.good += IsGoodSolution(data, run.snapshot_object, run.object_template, hierarchical);
  }
  result.seconds = Seconds(start_time);
  return result;
}

int NearBest(const std::vector<double>& log_likelihoods, double tolerance) {
  if (log_likelihoods.empty()) return 0;
  const double best = *std::max_element(log_likelihoods.begin(), log_likelihoods.end());
  return static_cast<int>(std::count_if(log_likelihoods.begin(), log_likelihoods.end(),
                                        [&](double ll) { return ll >= best - tolerance; }));
}

int ObjectsToLearn(const ObjectDataset& data, const ol::EmProblem& problem) {
  return std::max(data.true_objects, problem.max_per_map());
}

double LeaveOneMapOutLogLikelihood(const ol::EmProblem& problem, int num_objects, int num_templates,
                                   const ol::LearnOptions& options) {
  double sum = 0.0;
  for (size_t t = 0; t < problem.maps.size(); ++t) {
    if (problem.maps[t].empty()) continue;
    const ol::EmProblem train = WithoutMap(problem, static_cast<int>(t));
    if (train.snapshots.size() < static_cast<size_t>(num_objects)) continue;
    const ol::EmResult model = ol::BestOfRestarts(train, num_objects, num_templates, options);
    std::vector<scene::Patch> held_out;
    for (int s : problem.maps[t]) held_out.push_back(problem.snapshots[s]);
    sum += ol::HeldOutLogLikelihood(held_out, model.objects, options.em);
  }
  return sum;
}

ObjectExperimentResult RunObjectExperiment(const ObjectDataset& data, int starts,
                                           const ol::LearnOptions& options) {
  ObjectExperimentResult result;
  result.maps = static_cast<int>(data.maps.size());
  result.snapshots = static_cast<int>(data.snapshots.snapshots.size());
  result.per_map = data.snapshots.per_map;
  for (int t : data.snapshot_truth) result.spurious_snapshots += t < 0;
  result.true_objects = data.true_objects;
  result.true_templates = data.true_templates;
  const ol::EmProblem problem = ol::MakeEmProblem(data.snapshots);
  const int n = ObjectsToLearn(data, problem);
  const int m = data.true_templates;

  for (const bool hierarchical : {true, false}) {
    ModelComparison& c = hierarchical ? result.hierarchical : result.flat;
    c.model = hierarchical ? "hierarchical" : "flat";
    c.starts = starts;
    ol::LearnOptions run_options = options;
    run_options.hierarchical = hierarchical;
    const RandomStarts random_starts =
        RunRandomStarts(data, problem, n, m, hierarchical, starts, run_options);
    c.good = random_starts.good;
    c.train_log_likelihood = random_starts.train_log_likelihood;
    c.seconds_starts = random_starts.seconds;
    auto start_time = std::chrono::steady_clock::now();
    c.test_log_likelihood = LeaveOneMapOutLogLikelihood(problem, n, m, run_options);
    c.seconds_cross_validation = Seconds(start_time);
    // Model selection.
    start_time = std::chrono::steady_clock::now();
    const ol::SelectionResult selection = ol::SelectModel(problem, run_options);
    c.seconds_selection = Seconds(start_time);
    c.chosen_objects = selection.num_objects;
    c.chosen_templates = selection.num_templates;
    c.searched = selection.searched;
  }
  return result;
}

}  // namespace fleetmap::bench
