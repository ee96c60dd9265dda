#pragma once

// How speckled a map is: a census of the lone clusters of occupied cells in its free space, the
// marks SLAM noise (and small real things) leave, counted the same way on real maps and on the
// small-piece benchmark's synthetic noise so that the benchmark's "speck events per 100 m2" can be
// read against real robots' maps (issue 36, item 3; docs/object-learning.md, "Small objects
// against SLAM specks").
//
// A lone cluster: an 8-connected group of occupied cells of at most `max_cells` cells with no
// other occupied cell within `isolation_m` of its bounding box, and at least three quarters of
// the cells there known free (specks in unknown space or in a ragged wall are not counted: the
// census is a floor of the noise near walls, a ceiling in open space, where a leg or a bin counts
// as a speck). Compact as the snapshot extractor's rule for small objects: a bounding box of at
// most 3 cells a side at least half filled. Cells are the map's own: at other resolutions than
// 5 cm the same counts mean other sizes.
//
// Thread-safety: stateless.

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct SpeckCensusOptions {
  double isolation_m = 0.4;
  int max_cells = 8;
};

struct SpeckCensus {
  double free_area_m2 = 0.0;
  int lone_specks = 0;    // lone clusters of 1-3 cells
  int lone_clusters = 0;  // lone clusters of 4 to max_cells cells
  int lone_compact = 0;   // of those, compact and of at most 7 cells: a small object's look

  // Per 100 m2 of free space (0 for a map with none).
  double Per100m2(int count) const {
    return free_area_m2 > 0.0 ? 100.0 * count / free_area_m2 : 0.0;
  }
  void Add(const SpeckCensus& other) {
    free_area_m2 += other.free_area_m2;
    lone_specks += other.lone_specks;
    lone_clusters += other.lone_clusters;
    lone_compact += other.lone_compact;
  }
};

SpeckCensus CountLoneSpecks(const grid::OccupancyGrid& map, const SpeckCensusOptions& options = {});

}  // namespace fleetmap::bench
