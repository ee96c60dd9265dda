#include "common/object_learning/object_learner.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "common/object_learning/em_problem.hpp"
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
                                    const LearnOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  FLEETMAP_ASSIGN_OR_RETURN(SnapshotSet set, ExtractSnapshots(maps, options.snapshots));
  LearnedModel model;
  model.warnings = set.warnings;
  if (set.snapshots.empty()) {
    model.warnings.push_back("no object moved between the " + std::to_string(maps.size()) +
                             " maps: nothing to learn (0 objects, 0 templates)");
    return model;
  }
  const EmProblem problem = MakeEmProblem(set);
  SelectionResult selection = SelectModel(problem, options);
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
  return model;
}

}  // namespace fleetmap::object_learning
