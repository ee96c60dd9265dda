#include "common/object_learning/hierarchical_em.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "common/core/check.hpp"
#include "common/object_learning/alignment_search.hpp"
#include "common/object_learning/e_step.hpp"
#include "common/object_learning/m_step.hpp"
#include "common/object_learning/patch_transform.hpp"

namespace fleetmap::object_learning {
namespace {

scene::Patch RowPatch(const Eigen::MatrixXd& rows, Eigen::Index row, const scene::Patch& shape) {
  scene::Patch patch = ZeroPatch(shape.width, shape.height, shape.resolution);
  for (Eigen::Index i = 0; i < rows.cols(); ++i)
    patch.occupancy[i] = static_cast<float>(rows(row, i));
  return patch;
}

// A re-framing smaller than this (half a cell, two degrees) is not worth the resampling (which
// blurs the object a little each time).
bool Negligible(const Alignment& a, double resolution) {
  return std::hypot(a.dx, a.dy) < 0.5 * resolution && std::abs(a.dphi) < 0.035;
}

// The template step: aligns every object to every template (eps_n,m, by the same search as
// snapshots), returns -min |g(theta_n, eps) - alpha_m|^2 / (2 tau^2), and re-frames each object
// onto its most likely template: theta_n is moved by eps_n,m* and the moves are composed into the
// object's snapshot alignments, which leaves the data term unchanged. Objects and templates are
// compared cell by cell (eq. 4), so an object must stand in its template's frame, and a random
// start gives each object the frame of the snapshot it started from.
Eigen::MatrixXd TemplateStep(const EmProblem& problem, const Eigen::MatrixXd& templates, double tau,
                             bool scan, const EmOptions& options, Eigen::MatrixXd* objects,
                             PairAlignments* object_to_template,
                             PairAlignments* snapshot_to_object) {
  const Eigen::Index n_count = objects->rows(), m_count = templates.rows();
  const scene::Patch& shape = problem.snapshots.front();
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      templates.cast<float>();
  Eigen::MatrixXd log_weights(n_count, m_count);
  for (Eigen::Index n = 0; n < n_count; ++n) {
    const scene::Patch object = RowPatch(*objects, n, shape);
    for (Eigen::Index m = 0; m < m_count; ++m) {
      const AlignmentResult r = AlignSnapshot(object, targets.row(m).data(),
                                              (*object_to_template)[n][m], scan, 0.25, options);
      (*object_to_template)[n][m] = r.alignment;
      log_weights(n, m) = -r.squared_distance / (2.0 * tau * tau);
    }
    Eigen::Index best = 0;
    log_weights.row(n).maxCoeff(&best);
    const Alignment move = (*object_to_template)[n][best];
    if (Negligible(move, shape.resolution)) continue;
    scene::Patch moved;
    TransformPatch(object, move, &moved);
    for (Eigen::Index i = 0; i < objects->cols(); ++i) (*objects)(n, i) = moved.occupancy[i];
    for (std::vector<Alignment>& pairs : *snapshot_to_object) pairs[n] = Compose(move, pairs[n]);
    const Alignment undo = Inverse(move);
    for (Eigen::Index m = 0; m < m_count; ++m) {
      (*object_to_template)[n][m] = Compose((*object_to_template)[n][m], undo);
    }
  }
  return log_weights;
}

// The template level's global move. EM's template step is k-means-like and keeps a grouping
// once made: two shapes sharing a template while two objects of one shape hold a template each is
// a local maximum it does not leave. At rotation-scan iterations the objects are re-grouped by
// k-medoids on their aligned pairwise distances (seeded restarts); when that grouping explains
// the objects better than the current one (sum of distances to the group's medoid), each template
// restarts from its group's medoid. Returns whether the templates were re-seeded.
bool RegroupTemplates(const EmProblem& problem, const Eigen::MatrixXd& responsibilities,
                      const EmOptions& options, std::mt19937_64* random,
                      const Eigen::MatrixXd& objects, Eigen::MatrixXd* templates,
                      PairAlignments* object_to_template) {
  const int n_count = static_cast<int>(objects.rows());
  const int m_count = static_cast<int>(templates->rows());
  if (m_count < 2 || m_count >= n_count) return false;
  const scene::Patch& shape = problem.snapshots.front();
  // distance(n, k): object n aligned onto object k.
  Eigen::MatrixXd distance = Eigen::MatrixXd::Zero(n_count, n_count);
  PairAlignments onto(n_count, std::vector<Alignment>(n_count));
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> targets =
      objects.cast<float>();
  std::vector<ShapeSize> sizes;
  for (int n = 0; n < n_count; ++n) {
    sizes.push_back(SizeOfContent(targets.row(n).data(), shape.width, shape.height));
  }
  for (int n = 0; n < n_count; ++n) {
    const scene::Patch object = RowPatch(objects, n, shape);
    for (int k = 0; k < n_count; ++k) {
      if (k == n) continue;
      // Unlike objects are far apart at any rotation: their unturned distance is enough to
      // keep them in different groups, without a scan.
      const AlignmentResult r =
          MayMatch(sizes[n], sizes[k])
              ? AlignSnapshot(object, targets.row(k).data(), Alignment{}, true, 1.0, options)
              : CentroidAlignment(object, targets.row(k).data());
      distance(n, k) = r.squared_distance;
      onto[n][k] = r.alignment;
    }
  }
  auto cost_of = [&](const std::vector<int>& medoids) {
    double cost = 0.0;
    for (int n = 0; n < n_count; ++n) {
      double best = std::numeric_limits<double>::infinity();
      for (int k : medoids) best = std::min(best, distance(n, k));
      cost += best;
    }
    return cost;
  };
  // The current grouping's cost: each template's group around its best medoid.
  double current = 0.0;
  for (int m = 0; m < m_count; ++m) {
    std::vector<int> group;
    for (int n = 0; n < n_count; ++n) {
      Eigen::Index best = 0;
      responsibilities.row(n).maxCoeff(&best);
      if (best == m) group.push_back(n);
    }
    double best_group = group.empty() ? 0.0 : std::numeric_limits<double>::infinity();
    for (int k : group) {
      double c = 0.0;
      for (int n : group) c += distance(n, k);
      best_group = std::min(best_group, c);
    }
    current += best_group;
  }
  // k-medoids (Voronoi iteration) from k-means++ seeds.
  constexpr int kRestarts = 16;
  std::vector<int> best_medoids;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int restart = 0; restart < kRestarts; ++restart) {
    std::vector<int> medoids = {
        std::min(n_count - 1, static_cast<int>(UniformDouble(random) * n_count))};
    while (static_cast<int>(medoids.size()) < m_count) {
      std::vector<double> nearest(n_count);
      double total = 0.0;
      for (int n = 0; n < n_count; ++n) {
        nearest[n] = std::numeric_limits<double>::infinity();
        for (int k : medoids) nearest[n] = std::min(nearest[n], distance(n, k));
        total += nearest[n];
      }
      double u = UniformDouble(random) * total;
      int next = -1;
      for (int n = 0; n < n_count; ++n) {
        if (std::find(medoids.begin(), medoids.end(), n) != medoids.end()) continue;
        next = n;
        if (u < nearest[n]) break;
        u -= nearest[n];
      }
      medoids.push_back(next);
    }
    for (int round = 0; round < 10; ++round) {
      bool changed = false;
      for (int m = 0; m < m_count; ++m) {
        std::vector<int> group;
        for (int n = 0; n < n_count; ++n) {
          int nearest = 0;
          for (int q = 1; q < m_count; ++q) {
            if (distance(n, medoids[q]) < distance(n, medoids[nearest])) nearest = q;
          }
          if (nearest == m) group.push_back(n);
        }
        double best_c = std::numeric_limits<double>::infinity();
        int best_k = medoids[m];
        for (int k : group) {
          double c = 0.0;
          for (int n : group) c += distance(n, k);
          if (c < best_c - 1e-12) best_c = c, best_k = k;
        }
        if (best_k != medoids[m]) medoids[m] = best_k, changed = true;
      }
      if (!changed) break;
    }
    const double cost = cost_of(medoids);
    if (cost < best_cost) best_cost = cost, best_medoids = medoids;
  }
  // Only a clear gain is worth restarting the templates for.
  if (!(best_cost < 0.95 * current - 1e-9)) return false;
  for (int m = 0; m < m_count; ++m) {
    const int k = best_medoids[m];
    templates->row(m) = objects.row(k);
    for (int n = 0; n < n_count; ++n)
      (*object_to_template)[n][m] = n == k ? Alignment{} : onto[n][k];
  }
  return true;
}

// Converged: annealing is over and nothing moves any more.
constexpr double kExpectationTolerance = 1e-3;
constexpr double kModelTolerance = 1e-2;  // occupancy: a percent

}  // namespace

double ObjectLevelLogLikelihood(const Eigen::MatrixXd& log_weights, Eigen::Index cells,
                                double tau) {
  double sum = 0.0;
  for (Eigen::Index n = 0; n < log_weights.rows(); ++n) {
    sum += LogSumExp(log_weights.row(n).transpose()) -
           std::log(static_cast<double>(log_weights.cols()));
  }
  return sum + GaussianLogConstant(static_cast<double>(log_weights.rows()) * cells, tau);
}

EmResult RunHierarchicalEm(const EmProblem& problem, int num_objects, int num_templates,
                           const EmOptions& options, uint64_t seed,
                           const std::function<void(int)>& on_iteration) {
  FLEETMAP_CHECK(num_templates >= 1 && num_templates <= num_objects);
  FLEETMAP_CHECK(num_objects >= problem.max_per_map());
  std::mt19937_64 random(seed);
  EmResult r;
  RandomStart(problem, num_objects, options, &random, &r.objects, &r.alignments);
  // Templates start as M of the objects, spread out as k-means++ does: each next one drawn with
  // probability proportional to its squared distance (at its best alignment) to the nearest one
  // already drawn.
  r.templates.resize(num_templates, problem.cells());
  {
    const scene::Patch& shape = problem.snapshots.front();
    std::vector<int> chosen = {
        std::min(num_objects - 1, static_cast<int>(UniformDouble(&random) * num_objects))};
    std::vector<double> nearest(num_objects, std::numeric_limits<double>::infinity());
    while (static_cast<int>(chosen.size()) < num_templates) {
      const Eigen::Matrix<float, 1, Eigen::Dynamic> target =
          r.objects.row(chosen.back()).cast<float>();
      double total = 0.0;
      for (int n = 0; n < num_objects; ++n) {
        const double d = AlignSnapshot(RowPatch(r.objects, n, shape), target.data(), Alignment{},
                                       true, 1.0, options)
                             .squared_distance;
        nearest[n] = std::min(nearest[n], d);
        total += nearest[n];
      }
      double u = UniformDouble(&random) * total;
      int next = -1;
      for (int n = 0; n < num_objects; ++n) {
        if (std::find(chosen.begin(), chosen.end(), n) != chosen.end()) continue;
        next = n;  // the last unchosen object if rounding leaves u > 0
        if (u < nearest[n]) break;
        u -= nearest[n];
      }
      chosen.push_back(next);
    }
    for (int m = 0; m < num_templates; ++m) r.templates.row(m) = r.objects.row(chosen[m]);
  }
  PairAlignments object_to_template(num_objects, std::vector<Alignment>(num_templates));
  Eigen::MatrixXd previous_c, previous_z;
  bool reseeded = false;
  for (int j = 0; j < options.iterations; ++j) {
    const double sigma = Annealed(options.sigma, options.sigma_initial, options.annealing, j);
    const double tau = Annealed(options.tau, options.tau_initial, options.annealing, j);
    const bool scan = j % options.rotation_scan_every == 0;
    const Eigen::MatrixXd log_weights = TemplateStep(
        problem, r.templates, tau, scan, options, &r.objects, &object_to_template, &r.alignments);
    r.responsibilities = Responsibilities(log_weights);
    const CorrespondenceStep c = CorrespondenceEStep(
        problem, SnapshotLogLikelihoods(problem, r.alignments, r.objects, sigma), options, &random);
    r.approximate = r.approximate || c.approximate;
    r.correspondences = c.expectations;
    const Eigen::MatrixXd previous_objects = r.objects;
    HierarchicalParameters p =
        HierarchicalMStep(WeightedSnapshotSums(problem, r.alignments, r.correspondences, r.objects),
                          r.correspondences, r.responsibilities, sigma, tau, r.templates);
    r.objects = std::move(p.objects);
    r.templates = std::move(p.templates);
    reseeded = scan && RegroupTemplates(problem, r.responsibilities, options, &random, r.objects,
                                        &r.templates, &object_to_template);
    AlignmentStep(problem, r.correspondences, r.objects, scan, options, &r.alignments);
    r.iterations = j + 1;
    if (on_iteration) on_iteration(r.iterations);
    const bool annealed = sigma == options.sigma && tau == options.tau;
    if (annealed && !reseeded && previous_c.size() == r.correspondences.size() &&
        (r.correspondences - previous_c).cwiseAbs().maxCoeff() < kExpectationTolerance &&
        (r.responsibilities - previous_z).cwiseAbs().maxCoeff() < kExpectationTolerance &&
        (r.objects - previous_objects).cwiseAbs().maxCoeff() < kModelTolerance) {
      break;
    }
    previous_c = r.correspondences;
    previous_z = r.responsibilities;
  }

  // The final E-step and the log joint at the final noise levels.
  const Eigen::MatrixXd template_log_weights =
      TemplateStep(problem, r.templates, options.tau, false, options, &r.objects,
                   &object_to_template, &r.alignments);
  r.responsibilities = Responsibilities(template_log_weights);
  const Eigen::MatrixXd ll =
      SnapshotLogLikelihoods(problem, r.alignments, r.objects, options.sigma);
  const CorrespondenceStep c = CorrespondenceEStep(problem, ll, options, &random);
  r.approximate = r.approximate || c.approximate;
  r.correspondences = c.expectations;
  r.snapshot_object = MapAssignments(problem, ll, options);
  r.object_template.resize(num_objects);
  for (int n = 0; n < num_objects; ++n) {
    Eigen::Index best = 0;
    r.responsibilities.row(n).maxCoeff(&best);
    r.object_template[n] = static_cast<int>(best);
  }
  r.log_likelihood = c.log_likelihood + GaussianLogConstant(ObservedCells(problem), options.sigma) +
                     ObjectLevelLogLikelihood(template_log_weights, r.objects.cols(), options.tau);
  return r;
}

}  // namespace fleetmap::object_learning
