#pragma once

// Map differencing (ALGORITHMS.md 2, "Snapshot extraction"): cuts one snapshot per moved object
// out of every map. A cell of map t is a difference when it is occupied in t and free in some
// other map t' with only free cells of t' within SnapshotOptions::guard_radius; a low-pass filter
// (box mean) removes the speckle along occupied/free borders; region growing (cells up to
// SnapshotOptions::link_cells apart) makes one
// region per object, which is cropped into a patch centred on the region's centroid cell. Every
// patch has the same size (the largest region's, plus a margin, unless patch_cells is set).
//
// Objects that touch (no free cell between them) form one region and so one snapshot: the
// method's known limit (docs/object-learning.md).
//
// Thread-safety: stateless.

#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/alignment.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

struct Snapshot {
  int map_index = 0;
  Point2 centre = Point2::Zero();  // map frame, metres: centre of the patch's centre cell
  int cells = 0;                   // cells in the region
  // 1 on the region's cells, 0 elsewhere, smoothed (SnapshotOptions::blur_cells); weight 1 where
  // the map saw the cell free or it is the region's, 0 where it is unknown or another obstacle.
  scene::Patch patch;
};

struct SnapshotSet {
  std::vector<Snapshot> snapshots;  // grouped by map, maps in order
  std::vector<int> per_map;         // K_t, snapshots of each map
  std::vector<std::string> warnings;
};

// Regions larger than the limits are split (region_splitter.hpp); regions below
// min_region_cells are kept only when they are compact and recur, or are compact and alone
// (SnapshotOptions::small_region_cells, isolation_radius_m).
// Maps before `first_map` are left out (a learner over its memory budget drops the oldest
// sessions); snapshot map indices stay those of `maps`, and per_map has a 0 for each left out.
// Errors (kInvalidArgument): fewer than two maps (from first_map on), maps whose size, resolution
// or origin differ (naming the two map indices), snapshot options out of range.
StatusOr<SnapshotSet> ExtractSnapshots(const std::vector<grid::OccupancyGrid>& maps,
                                       const SnapshotOptions& options, size_t first_map = 0);

// Kinds of geometry mismatch, for callers that name files: "" when `a` and `b` share size,
// resolution and origin, otherwise what differs ("size 100 x 80 vs 120 x 80 cells").
std::string GeometryMismatch(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b);

}  // namespace fleetmap::object_learning
