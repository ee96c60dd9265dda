#pragma once

// Small objects against SLAM specks (issue 36, item 3; docs/object-learning.md, "Small objects and
// specks"): map pairs of a 20 x 15 m floor at 5 cm, differenced by ExtractSnapshots.
// - A furnished pair: furniture (12-200 cells) and small pieces (4-7 cells: 2 x 2, plus sign,
//   2 x 3, an L of 7; 10-15 cm: bins, chair and table legs), at least 0.6 m from each other and the
//   walls; each piece shows in one map only (it appeared or went away) or moves between the two.
//   Both maps also get specks.
// - A noise-only pair: the same floor, no piece, specks only.
// Specks, per map, `speck_events_per_100m2` events at random places in free space, each one of:
//   scatter (50 %): 3-8 single cells within 0.4 m (a reflection, a person's legs over a few scans);
//   strand (30 %): 4-8 cells in a row or column (specks along a scan line);
//   blob (20 %): 2-4 cells grown at random from one cell (a leg seen in one scan).
// A piece is found when a snapshot of its map has its centre within 0.15 m of the piece's; a
// snapshot near no piece of its map is a false object.
//
// Thread-safety: stateless.

#include <cstdint>
#include <string>

#include "bench/objects/speck_census.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/learn_options.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {

struct SmallPieceOptions {
  uint32_t seed = 1;
  int pairs = 20;
  int furniture = 12;     // per pair
  int small_pieces = 24;  // per pair
  double speck_events_per_100m2 = 5.0;
  // Every small piece in map 0 only (it appeared; map 1 has no small piece to recur with), the
  // case of issue 36.
  bool small_in_one_map = false;
  object_learning::SnapshotOptions snapshots;
};

struct SmallPieceResult {
  // Furnished pairs: pieces in a map (a moved piece counts in both), found, snapshots, false.
  int small = 0, small_found = 0;  // 4-7 cells
  int furniture = 0, furniture_found = 0;
  int snapshots = 0, false_objects = 0;
  // Noise-only pairs.
  int noise_snapshots = 0;
  double noise_area_m2 = 0.0;  // free floor of both maps of every noise-only pair
  SpeckCensus noise_census;    // the lone clusters of every noise-only map (speck_census.hpp)
};

// The benchmark's empty floor with `events_per_100m2` speck events (the noise-only maps).
grid::OccupancyGrid SpeckledFloor(double events_per_100m2, sim::Random* random);

// Errors: bad options.
StatusOr<SmallPieceResult> RunSmallPieceExperiment(const SmallPieceOptions& options);

// The Markdown report of a run (command, machine, table).
std::string SmallPieceReport(const SmallPieceOptions& options, const SmallPieceResult& result);

}  // namespace fleetmap::bench
