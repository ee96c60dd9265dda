#include "bench/objects/contrast_experiment.hpp"

#include <cmath>
#include <utility>

#include "common/object_learning/em_problem.hpp"

namespace fleetmap::bench {
namespace {

using sim::MovableShape;

// Four chairs and four boxes: many objects, two shapes.
std::vector<MovableShape> ManyOfFew() {
  return {MovableShape::kChair, MovableShape::kChair, MovableShape::kChair, MovableShape::kChair,
          MovableShape::kBox,   MovableShape::kBox,   MovableShape::kBox,   MovableShape::kBox};
}

ContrastCondition Variant(ContrastCondition base, std::string name, std::string changed) {
  base.name = std::move(name);
  base.changed = std::move(changed);
  return base;
}

// Sigma and tau at their final values from the first iteration: a random start's first
// correspondences are as sharp as the last ones.
ContrastCondition WithoutAnnealing(ContrastCondition condition) {
  condition.learn.em.sigma_initial = condition.learn.em.sigma;
  condition.learn.em.tau_initial = condition.learn.em.tau;
  return condition;
}

}  // namespace

std::vector<ContrastCondition> ContrastConditions() {
  std::vector<ContrastCondition> conditions;
  ContrastCondition paper;
  paper.name = "paper";
  paper.changed = "none: 2 chairs, a bin, a box; 9 sessions of 2-3 objects; 10 m lab";
  conditions.push_back(paper);

  ContrastCondition many =
      Variant(paper, "many-of-few", "4 chairs and 4 boxes; 8 sessions of 4-6 objects; 14 m lab");
  many.data.size = 14.0;
  many.data.plan.shapes = ManyOfFew();
  many.data.plan.sessions = 8;
  many.data.plan.min_present = 4;
  many.data.plan.max_present = 6;
  conditions.push_back(many);

  ContrastCondition sparse = Variant(
      many, "seen-once", "4 chairs and 4 boxes; 4 sessions of 4-6 objects, an object in 1 or more");
  sparse.data.plan.sessions = 4;
  sparse.data.plan.min_sessions_per_object = 1;
  conditions.push_back(sparse);

  conditions.push_back(WithoutAnnealing(
      Variant(paper, "no-annealing",
              "the paper's data; sigma and tau at their final values from the first iteration")));

  ContrastCondition coarse =
      Variant(paper, "coarse-turns",
              "the paper's data; rotation scans every 45 degrees, once (poor alignments)");
  coarse.learn.em.rotation_scan_step = M_PI / 4.0;
  coarse.learn.em.rotation_scan_every = coarse.learn.em.iterations;
  conditions.push_back(coarse);

  ContrastCondition sharp =
      Variant(paper, "unsmoothed",
              "the paper's data; snapshots not smoothed (outlines one or two cells thick)");
  sharp.learn.snapshots.blur_cells = 0.0;
  conditions.push_back(sharp);

  conditions.push_back(
      WithoutAnnealing(Variant(many, "many-no-annealing", "many-of-few's data; no annealing")));
  return conditions;
}

StatusOr<ContrastRow> RunContrastCondition(const ContrastCondition& condition,
                                           const ContrastRunOptions& options) {
  ContrastRow row;
  row.condition = condition.name;
  row.changed = condition.changed;
  row.data_sets = options.data_sets;
  for (int i = 0; i < options.data_sets; ++i) {
    ObjectDatasetOptions data_options = condition.data;
    data_options.seed = options.first_seed + static_cast<uint32_t>(i);
    FLEETMAP_ASSIGN_OR_RETURN(const ObjectDataset data,
                              MakeObjectDataset(data_options, condition.learn.snapshots));
    const object_learning::EmProblem problem = object_learning::MakeEmProblem(data.snapshots);
    row.maps += static_cast<int>(data.maps.size());
    row.snapshots += static_cast<int>(data.snapshots.snapshots.size());
    row.true_objects = data.true_objects;
    row.true_templates = data.true_templates;
    row.starts += options.starts;
    const int n = ObjectsToLearn(data, problem);
    const int m = data.true_templates;
    object_learning::LearnOptions learn = condition.learn;
    learn.seed = data_options.seed;
    for (const bool hierarchical : {true, false}) {
      learn.hierarchical = hierarchical;
      const RandomStarts run =
          RunRandomStarts(data, problem, n, m, hierarchical, options.starts, learn);
      ContrastModel& total = hierarchical ? row.hierarchical : row.flat;
      total.good += run.good;
      total.near_best += NearBest(run.train_log_likelihood, options.near_best_nats);
      total.seconds += run.seconds;
      total.train_log_likelihood.insert(total.train_log_likelihood.end(),
                                        run.train_log_likelihood.begin(),
                                        run.train_log_likelihood.end());
      if (options.cross_validate) {
        total.test_log_likelihood += LeaveOneMapOutLogLikelihood(problem, n, m, learn);
      }
    }
  }
  return row;
}

}  // namespace fleetmap::bench
