#pragma once

// Every threshold and parameter of object learning, with its default (docs/object-learning.md has
// the reasons). One struct per component, gathered in LearnOptions; each checks itself with
// Validate() (kInvalidArgument naming the first bad option, e.g. "em.annealing 1.5 must be in
// (0, 1)"), LearnOptions recursing into its parts, once, where they are made.

#include <atomic>
#include <cstdint>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/learn_progress.hpp"

namespace fleetmap::object_learning {

// Map differencing (SnapshotExtractor). A cell of map t is a difference when it is occupied in t
// and free in some other map t' with only free cells of t' within `guard_radius` (a wall seen one
// cell further in t', or a wall face a grazing ray cleared, is not a moved object); the difference
// mask is low-pass filtered (box mean
// over (2 filter_radius + 1)^2 cells, kept where >= filter_threshold) against the speckle along
// occupied/free borders; region growing (cells up to link_cells apart) makes one snapshot per
// region.
struct SnapshotOptions {
  grid::StateThresholds thresholds;  // how a map cell reads as occupied / free
  int guard_radius = 1;              // cells, >= 0
  int filter_radius = 1;             // cells, >= 0 (0: no filter)
  double filter_threshold = 0.25;    // in [0, 1]
  // Region growing joins difference cells up to this many cells apart (Chebyshev distance), so an
  // object whose outline is seen with a gap stays one snapshot; objects closer than this merge.
  int link_cells = 3;        // >= 1 (1: 8-connected)
  int min_region_cells = 8;  // smaller regions are noise, >= 1, unless they recur (below)
  // A region of at least small_region_cells (and fewer than min_region_cells) is kept when a
  // region of a similar size (cells within a factor of 1.5, bounding box within a cell) appears in
  // another map: a bin of a few cells that moves recurs; lone speckle is dropped.
  // Not 3: a 3-cell blob is what SLAM speckle leaves at any resolution (the real maps' specks are
  // 1-3 cells), in every map, so another of its size elsewhere is no evidence; at 5 speck events
  // per 100 m2 such twins were 86 % of the false objects (docs/results.md).
  // 0: never (the old behaviour). In [0, min_region_cells].
  int small_region_cells = 4;
  // A small region that does not recur is kept too when it is compact (bounding box at most
  // 3 x 3 cells and at least half filled: a bin, a table leg) and isolated: no other difference
  // cell of its map, speckle the low-pass filter removed included, within isolation_radius_m of
  // its bounding box. SLAM specks come scattered (several within half a metre) or as thin strands
  // along a scan line; a piece of furniture stands alone. 0: never (recurrence only).
  double isolation_radius_m = 0.5;  // metres, in [0, 5]
  // Larger regions (a row of desks, furniture against furniture) are split into objects: first
  // into the parts that are apart at all (8-connected), then at their narrow necks (the cells
  // left by erosion seed a geodesic watershed), and a part that is still too large is cut into
  // slices across its long axis (with a warning). A region wider than 2 max_region_radius_m
  // is split the same way: one size is shared by every patch, so one huge region would make
  // every patch (and the time and memory of learning) huge.
  int max_region_cells = 4000;       // >= min_region_cells
  double max_region_radius_m = 1.5;  // metres from its centroid to its farthest cell, > 0
  int margin_cells = 3;              // empty border around the largest snapshot, >= 0
  int patch_cells = 0;               // side of every patch in cells; 0: from the largest snapshot
  // Gaussian smoothing of each snapshot patch (standard deviation, cells; 0: none). A laser sees
  // an object's outline, one or two cells thick: unsmoothed, two outlines one cell apart share no
  // cell, and alignment has no slope to climb.
  double blur_cells = 1.0;  // in [0, 10]

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// One EM run (HierarchicalEm, FlatEm) for a fixed (N, M).
struct EmOptions {
  double sigma = 0.25;  // snapshot noise (eq. 1), final value, > 0
  // Object-to-template noise (eq. 4), final value, > 0. At 1 / sqrt(2 pi) the Gaussian's
  // normalising constant is 1, so an extra object is not rewarded by the density of its cells
  // (which would otherwise add -cells * log(sqrt(2 pi) tau) nats per object to the log posterior).
  double tau = 0.3989422804014327;
  double sigma_initial = 2.0;  // annealing start (eq. 27), >= sigma
  double tau_initial = 1.0;    // annealing start (eq. 28), >= tau
  double annealing = 0.85;     // kappa in (0, 1)
  int iterations = 30;         // EM iterations per run, >= 1
  // Alignment search (hill climbing over dx, dy, dphi), seeded by a coarse scan over rotations
  // every `rotation_scan_every` iterations (objects are seen in any orientation, and a local
  // climb cannot turn a snapshot by 90 degrees).
  double rotation_scan_step = 0.2617993877991494;  // radians (15 degrees), > 0
  int rotation_scan_every = 10;                    // iterations, >= 1
  double initial_shift_step = 0.1;                 // metres, > 0
  double initial_turn_step = 0.1308996938995747;   // radians (7.5 degrees), > 0
  double min_shift_step = 0.0125;                  // metres, > 0: the climb stops below
  // Above this many snapshots in one map the exact E-step (eq. 19) is replaced by Gibbs sampling
  // over injective assignments, and the result carries a warning.
  int max_exact_snapshots = 12;  // in [1, 20]
  int gibbs_sweeps = 200;        // samples kept, >= 1
  int gibbs_burn_in = 50;        // sweeps dropped, >= 0

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// The search over (N objects, M templates) (ModelSelection): max_t K_t <= N <= sum_t K_t,
// 1 <= M <= N, score log p(data, model) - object_penalty * N - template_penalty * M (eq. 30).
struct SelectionOptions {
  double object_penalty = 12.0;   // c_N, nats per object, >= 0
  double template_penalty = 5.0;  // c_M, nats per template, >= 0
  int max_objects = 16;           // cap on N (a warning says when it bites), >= 1
  // The search along N (and along M for each N) stops after this many candidates in a row
  // without a new best; 0 searches the whole grid.
  int patience = 1;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

struct LearnOptions {
  SnapshotOptions snapshots;
  EmOptions em;
  SelectionOptions selection;
  // Random starts per (N, M); the best is kept, >= 1. One start chose the same (N, M) as two on
  // all four benchmark data sets, in half the time (docs/results.md).
  int restarts = 1;
  uint32_t seed = 1;         // every random start derives from it: same seed, same model
  bool hierarchical = true;  // false: the flat model of Biswas et al. 2002 (objects only, M = 0)
  // When set (by another thread), learning stops before its next EM run and LearnObjects fails
  // with kUnavailable: a server shutting down need not wait for a run of several seconds.
  // Null: never cancelled. Must outlive the call.
  const std::atomic<bool>* cancel = nullptr;
  // Memory the learner may use, MB (its own tables; the input maps are the caller's). Before
  // each stage it estimates its peak (memory_plan.hpp); when that is over the budget it degrades
  // and says so in LearnedModel::warnings and `degraded`: the oldest maps left out of differencing,
  // one restart per (N, M), a lower exact E-step bound, patches coarsened (2x, 4x: coarser
  // alignment), the oldest maps left out (fewer sessions), and at last a cap on the objects
  // searched. It never fails for memory. > 0.
  double memory_budget_mb = 1024.0;
  // Time: one EM iteration costs about snapshots x objects x patch cells (every pair is resampled
  // and aligned). Above this product (at the fewest objects searched) the patches are coarsened
  // 2x (at most twice, and not beyond 10 cm cells; 4x fewer cells each time) and a warning says
  // so. The lab's 23 snapshots
  // x 4 objects x 29^2 cells are 7.7e4; 160 pieces of furniture x 40 objects x 39^2 cells 1e7.
  // > 0.
  double work_budget = 4e6;
  // Progress reports (learn_progress.hpp); empty: none.
  LearnProgressCallback progress;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

}  // namespace fleetmap::object_learning
