#include "common/object_learning/object_learner.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/memory_plan.hpp"
#include "common/object_learning/model_selection.hpp"
#include "common/object_learning/snapshot_extractor.hpp"

namespace fleetmap::object_learning {
namespace {

scene::Patch RowToPatch(const Eigen::MatrixXd& rows, Eigen::Index row, const scene::Patch& shape) {
  scene::Patch patch;
  patch.width = shape.width;
  patch.height = shape.height;
  patch.resolution = shape.resolution;
  patch.occupancy.resize(rows.cols());
  for (Eigen::Index i = 0; i < rows.cols(); ++i) {
    patch.occupancy[i] = static_cast<float>(std::clamp(rows(row, i), 0.0, 1.0));
  }
  return patch;
}

}  // namespace

Pose2 ObjectPoseInMap(const SnapshotAssignment& assignment) {
  const Alignment& a = assignment.alignment;
  const Point2 origin = assignment.centre - Eigen::Rotation2Dd(-a.dphi) * Point2(a.dx, a.dy);
  return {origin.x(), origin.y(), NormalizeAngle(-a.dphi)};
}

StatusOr<LearnedModel> LearnObjects(const std::vector<grid::OccupancyGrid>& maps,
                                    const LearnOptions& given) {
  FLEETMAP_RETURN_IF_ERROR(given.Validate());
  LearnOptions options = given;  // the budget may lower some of them
  const auto start = std::chrono::steady_clock::now();
  LearnProgress progress;
  progress.maps = static_cast<int>(maps.size());
  auto report = [&](LearnStage stage) {
    if (!options.progress) return;
    progress.stage = stage;
    progress.elapsed_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.remaining_seconds = stage == LearnStage::kDone ? 0.0 : -1.0;
    options.progress(progress);
  };
  report(LearnStage::kExtracting);

  const double budget = options.memory_budget_mb * 1e6;
  std::vector<std::string> degraded;
  auto mb = [](double bytes) {
    std::ostringstream text;
    text << std::setprecision(3) << bytes / 1e6;
    return text.str();
  };
  // Fewer sessions: the oldest maps go first, while at least two are left.
  size_t first_map = 0;
  const int64_t map_cells = maps.empty() ? 0 : maps[0].cell_count();
  while (maps.size() - first_map > 2 &&
         ExtractionBytes(static_cast<int>(maps.size() - first_map), map_cells) > budget) {
    ++first_map;
  }
  if (first_map > 0) {
    degraded.push_back(
        "memory budget " + mb(budget) + " MB: differencing " + std::to_string(maps.size()) +
        " maps would take about " + mb(ExtractionBytes(static_cast<int>(maps.size()), map_cells)) +
        " MB; the oldest " + std::to_string(first_map) + " map(s) were left out (fewer sessions)");
  }
  const size_t first_map_for_differencing = first_map;
  FLEETMAP_ASSIGN_OR_RETURN(SnapshotSet set, ExtractSnapshots(maps, options.snapshots, first_map));
  // Learning: fewer restarts, exact E-step bound, coarser patches, fewer sessions, fewer objects,
  // in that order, until the estimate fits.
  int coarsened = 1;
  auto per_map = [&] {
    int most = 0;
    for (int k : set.per_map) most = std::max(most, k);
    return most;
  };
  auto objects_searched = [&] {
    const int total = static_cast<int>(set.snapshots.size());
    return std::max(per_map(), std::min(total, options.selection.max_objects));
  };
  auto learning_bytes = [&] {
    const int64_t cells =
        set.snapshots.empty()
            ? 0
            : static_cast<int64_t>(set.snapshots[0].patch.width) * set.snapshots[0].patch.height;
    return LearningBytes(static_cast<int>(set.snapshots.size()), cells, objects_searched(),
                         per_map(), options.em.max_exact_snapshots);
  };
  const double first_estimate = learning_bytes();
  if (learning_bytes() > budget && options.restarts > 1) {
    options.restarts = 1;
    degraded.push_back("memory budget " + mb(budget) + " MB: learning would take about " +
                       mb(first_estimate) + " MB; one random start per (N, M) instead of " +
                       std::to_string(given.restarts));
  }
  while (learning_bytes() > budget && options.em.max_exact_snapshots > 8 && per_map() > 8) {
    --options.em.max_exact_snapshots;
  }
  if (options.em.max_exact_snapshots < given.em.max_exact_snapshots) {
    degraded.push_back("memory budget " + mb(budget) + " MB: the exact E-step is used up to " +
                       std::to_string(options.em.max_exact_snapshots) +
                       " snapshots per map (em.max_exact_snapshots " +
                       std::to_string(given.em.max_exact_snapshots) + "), sampled above");
  }
  while (learning_bytes() > budget) {
    const int side = set.snapshots.empty() ? 0 : set.snapshots[0].patch.width;
    if (coarsened < 4 && side >= 15) {
      CoarsenSnapshots(&set);
      coarsened *= 2;
      continue;
    }
    if (maps.size() - first_map > 2) {
      ++first_map;
      FLEETMAP_ASSIGN_OR_RETURN(set, ExtractSnapshots(maps, options.snapshots, first_map));
      for (int c = 1; c < coarsened; c *= 2) CoarsenSnapshots(&set);
      continue;
    }
    break;
  }
  auto cell_size = [&](int factor) {
    std::ostringstream text;
    text << factor * maps[0].resolution();
    return text.str();
  };
  if (coarsened > 1) {
    degraded.push_back("memory budget " + mb(budget) + " MB: learning would take about " +
                       mb(first_estimate) + " MB; snapshot patches were coarsened " +
                       std::to_string(coarsened) + "x (cells of " + cell_size(coarsened) +
                       " m: coarser alignment and templates)");
  }
  // Time: EM's cost grows with snapshots x objects x patch cells (every pair is resampled and
  // aligned). Past the work budget the patches are coarsened as for memory.
  auto work = [&] {
    const double cells = set.snapshots.empty() ? 0.0
                                               : static_cast<double>(set.snapshots[0].patch.width) *
                                                     set.snapshots[0].patch.height;
    return static_cast<double>(set.snapshots.size()) * std::max(1, per_map()) * cells;
  };
  const double first_work = work();
  const int coarsened_for_memory = coarsened;
  // Not coarser than 10 cm for time: a bin of 20 cm must stay more than a cell or two (memory
  // may coarsen further, above).
  constexpr double kCoarsestForWork = 0.1 + 1e-9;
  while (work() > options.work_budget && coarsened < 4 && !set.snapshots.empty() &&
         set.snapshots[0].patch.width >= 15 &&
         2.0 * set.snapshots[0].patch.resolution <= kCoarsestForWork) {
    CoarsenSnapshots(&set);
    coarsened *= 2;
  }
  if (coarsened > coarsened_for_memory) {
    std::ostringstream text;
    text << "work budget: " << set.snapshots.size() << " snapshots x " << per_map()
         << " objects x patch cells = " << first_work << " is above work_budget "
         << options.work_budget << "; snapshot patches were coarsened " << coarsened
         << "x (cells of " << cell_size(coarsened) << " m: coarser alignment and templates)";
    degraded.push_back(text.str());
  }
  if (first_map > first_map_for_differencing) {
    degraded.push_back("memory budget " + mb(budget) + " MB: the oldest " +
                       std::to_string(first_map) + " of " + std::to_string(maps.size()) +
                       " maps were left out (fewer sessions)");
  }
  while (learning_bytes() > budget && options.selection.max_objects > per_map() &&
         options.selection.max_objects > 1) {
    --options.selection.max_objects;
  }
  if (options.selection.max_objects < given.selection.max_objects) {
    degraded.push_back("memory budget " + mb(budget) + " MB: objects searched up to " +
                       std::to_string(objects_searched()) + " (selection.max_objects " +
                       std::to_string(given.selection.max_objects) + ")");
  }
  if (learning_bytes() > budget) {
    degraded.push_back("memory budget " + mb(budget) + " MB: still about " + mb(learning_bytes()) +
                       " MB after every degradation step; learning went ahead");
  }
  LearnedModel model;
  model.warnings = set.warnings;
  for (const std::string& d : degraded) model.warnings.push_back(d);
  model.degraded = !degraded.empty();
  model.estimated_memory_mb = learning_bytes() / 1e6;
  progress.snapshots = static_cast<int>(set.snapshots.size());
  if (set.snapshots.empty()) {
    model.warnings.push_back("no object moved between the " + std::to_string(maps.size()) +
                             " maps: nothing to learn (0 objects, 0 templates)");
    report(LearnStage::kDone);
    return model;
  }
  const EmProblem problem = MakeEmProblem(set);
  progress.elapsed_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SelectionResult selection = SelectModel(problem, options, progress);
  if (selection.cancelled) return UnavailableError("object learning was cancelled");
  const EmResult& best = selection.model;
  model.num_objects = selection.num_objects;
  model.num_templates = selection.num_templates;
  model.log_posterior = selection.log_posterior;
  model.searched = std::move(selection.searched);
  const scene::Patch& shape = problem.snapshots.front();
  for (Eigen::Index n = 0; n < best.objects.rows(); ++n) {
    model.objects.push_back(RowToPatch(best.objects, n, shape));
  }
  for (Eigen::Index m = 0; m < best.templates.rows(); ++m) {
    model.templates.push_back(RowToPatch(best.templates, m, shape));
  }
  model.object_template = best.object_template;
  for (size_t s = 0; s < set.snapshots.size(); ++s) {
    model.snapshots.push_back({set.snapshots[s].map_index, best.snapshot_object[s],
                               set.snapshots[s].centre,
                               best.alignments[s][best.snapshot_object[s]]});
  }
  for (std::string& w : selection.warnings) model.warnings.push_back(std::move(w));
  if (best.approximate) {
    model.warnings.push_back(
        "a map has more than " + std::to_string(options.em.max_exact_snapshots) +
        " snapshots (em.max_exact_snapshots): its correspondences were sampled (Gibbs), not "
        "summed exactly, and the log posterior is a lower bound");
  }
  progress.num_objects = model.num_objects;
  progress.num_templates = model.num_templates;
  progress.candidates_done = progress.candidates_estimate = static_cast<int>(model.searched.size());
  report(LearnStage::kDone);
  return model;
}

}  // namespace fleetmap::object_learning
