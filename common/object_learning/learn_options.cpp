#include "common/object_learning/learn_options.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace fleetmap::object_learning {
namespace {

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

Status Bad(const std::string& name, double value, const std::string& rule) {
  return InvalidArgumentError(name + " " + Number(value) + " is invalid: it must be " + rule);
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

Status SnapshotOptions::Validate() const {
  const SnapshotOptions& o = *this;
  const auto& t = o.thresholds;
  if (!(t.free >= 0.0 && t.free <= t.occupied && t.occupied <= 1.0)) {
    return InvalidArgumentError("snapshots.thresholds must satisfy 0 <= free <= occupied <= 1");
  }
  if (o.guard_radius < 0 || o.guard_radius > 20) {
    return Bad("snapshots.guard_radius", o.guard_radius, "in [0, 20]");
  }
  if (o.filter_radius < 0 || o.filter_radius > 20) {
    return Bad("snapshots.filter_radius", o.filter_radius, "in [0, 20]");
  }
  if (!(o.filter_threshold >= 0.0 && o.filter_threshold <= 1.0)) {
    return Bad("snapshots.filter_threshold", o.filter_threshold, "in [0, 1]");
  }
  if (o.link_cells < 1 || o.link_cells > 20) {
    return Bad("snapshots.link_cells", o.link_cells, "in [1, 20]");
  }
  if (o.min_region_cells < 1) return Bad("snapshots.min_region_cells", o.min_region_cells, ">= 1");
  if (o.small_region_cells < 0 || o.small_region_cells > o.min_region_cells) {
    return Bad("snapshots.small_region_cells", o.small_region_cells, "in [0, min_region_cells]");
  }
  if (!(o.isolation_radius_m >= 0.0 && o.isolation_radius_m <= 5.0)) {
    return Bad("snapshots.isolation_radius_m", o.isolation_radius_m, "in [0, 5]");
  }
  if (!Positive(o.max_region_radius_m)) {
    return Bad("snapshots.max_region_radius_m", o.max_region_radius_m, "> 0");
  }
  if (o.max_region_cells < o.min_region_cells) {
    return Bad("snapshots.max_region_cells", o.max_region_cells, ">= min_region_cells");
  }
  if (o.margin_cells < 0 || o.margin_cells > 100) {
    return Bad("snapshots.margin_cells", o.margin_cells, "in [0, 100]");
  }
  if (o.patch_cells < 0 || o.patch_cells > 1000) {
    return Bad("snapshots.patch_cells", o.patch_cells, "in [0, 1000] (0: automatic)");
  }
  if (!(o.blur_cells >= 0.0 && o.blur_cells <= 10.0)) {
    return Bad("snapshots.blur_cells", o.blur_cells, "in [0, 10]");
  }
  return Status::Ok();
}

Status EmOptions::Validate() const {
  const EmOptions& e = *this;
  if (!Positive(e.sigma)) return Bad("em.sigma", e.sigma, "> 0");
  if (!Positive(e.tau)) return Bad("em.tau", e.tau, "> 0");
  if (!(std::isfinite(e.sigma_initial) && e.sigma_initial >= e.sigma)) {
    return Bad("em.sigma_initial", e.sigma_initial, ">= em.sigma");
  }
  if (!(std::isfinite(e.tau_initial) && e.tau_initial >= e.tau)) {
    return Bad("em.tau_initial", e.tau_initial, ">= em.tau");
  }
  if (!(e.annealing > 0.0 && e.annealing < 1.0))
    return Bad("em.annealing", e.annealing, "in (0, 1)");
  if (e.iterations < 1 || e.iterations > 10000) {
    return Bad("em.iterations", e.iterations, "in [1, 10000]");
  }
  if (!Positive(e.rotation_scan_step))
    return Bad("em.rotation_scan_step", e.rotation_scan_step, "> 0");
  if (e.rotation_scan_every < 1)
    return Bad("em.rotation_scan_every", e.rotation_scan_every, ">= 1");
  if (!Positive(e.initial_shift_step)) {
    return Bad("em.initial_shift_step", e.initial_shift_step, "> 0");
  }
  if (!Positive(e.initial_turn_step))
    return Bad("em.initial_turn_step", e.initial_turn_step, "> 0");
  if (!Positive(e.min_shift_step)) return Bad("em.min_shift_step", e.min_shift_step, "> 0");
  if (e.max_exact_snapshots < 1 || e.max_exact_snapshots > 20) {
    return Bad("em.max_exact_snapshots", e.max_exact_snapshots, "in [1, 20]");
  }
  if (e.gibbs_sweeps < 1) return Bad("em.gibbs_sweeps", e.gibbs_sweeps, ">= 1");
  if (e.gibbs_burn_in < 0) return Bad("em.gibbs_burn_in", e.gibbs_burn_in, ">= 0");
  return Status::Ok();
}

Status SelectionOptions::Validate() const {
  const SelectionOptions& s = *this;
  if (!(std::isfinite(s.object_penalty) && s.object_penalty >= 0.0)) {
    return Bad("selection.object_penalty", s.object_penalty, ">= 0");
  }
  if (!(std::isfinite(s.template_penalty) && s.template_penalty >= 0.0)) {
    return Bad("selection.template_penalty", s.template_penalty, ">= 0");
  }
  if (s.max_objects < 1) return Bad("selection.max_objects", s.max_objects, ">= 1");
  if (s.patience < 0) return Bad("selection.patience", s.patience, ">= 0");
  return Status::Ok();
}

Status LearnOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(snapshots.Validate());
  FLEETMAP_RETURN_IF_ERROR(em.Validate());
  FLEETMAP_RETURN_IF_ERROR(selection.Validate());
  if (restarts < 1 || restarts > 1000) return Bad("restarts", restarts, "in [1, 1000]");
  if (!Positive(memory_budget_mb)) return Bad("memory_budget_mb", memory_budget_mb, "> 0");
  if (!Positive(work_budget)) return Bad("work_budget", work_budget, "> 0");
  return Status::Ok();
}

void SnapshotOptions::Describe(OptionsPrinter& out) const {
  out.Nested("thresholds", thresholds);
  out.Add("guard_radius", guard_radius);
  out.Add("filter_radius", filter_radius);
  out.Add("filter_threshold", filter_threshold);
  out.Add("link_cells", link_cells);
  out.Add("min_region_cells", min_region_cells);
  out.Add("small_region_cells", small_region_cells);
  out.Add("isolation_radius_m", isolation_radius_m);
  out.Add("max_region_cells", max_region_cells);
  out.Add("max_region_radius_m", max_region_radius_m);
  out.Add("margin_cells", margin_cells);
  out.Add("patch_cells", patch_cells);
  out.Add("blur_cells", blur_cells);
}

void EmOptions::Describe(OptionsPrinter& out) const {
  out.Add("sigma", sigma);
  out.Add("tau", tau);
  out.Add("sigma_initial", sigma_initial);
  out.Add("tau_initial", tau_initial);
  out.Add("annealing", annealing);
  out.Add("iterations", iterations);
  out.Add("rotation_scan_step", rotation_scan_step);
  out.Add("rotation_scan_every", rotation_scan_every);
  out.Add("initial_shift_step", initial_shift_step);
  out.Add("initial_turn_step", initial_turn_step);
  out.Add("min_shift_step", min_shift_step);
  out.Add("max_exact_snapshots", max_exact_snapshots);
  out.Add("gibbs_sweeps", gibbs_sweeps);
  out.Add("gibbs_burn_in", gibbs_burn_in);
}

void SelectionOptions::Describe(OptionsPrinter& out) const {
  out.Add("object_penalty", object_penalty);
  out.Add("template_penalty", template_penalty);
  out.Add("max_objects", max_objects);
  out.Add("patience", patience);
}

void LearnOptions::Describe(OptionsPrinter& out) const {
  out.Nested("snapshots", snapshots);
  out.Nested("em", em);
  out.Nested("selection", selection);
  out.Add("restarts", restarts);
  out.Add("seed", seed);
  out.Add("hierarchical", hierarchical);
  out.Add("memory_budget_mb", memory_budget_mb);
  out.Add("work_budget", work_budget);
}

}  // namespace fleetmap::object_learning
