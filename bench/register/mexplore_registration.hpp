#pragma once

// The baseline of the registration benchmark: m-explore's multirobot_map_merge (ROS 2 port,
// map_merge/src/combine_grids) estimating where one grid lies in another, reimplemented with
// OpenCV's stitching module the way its merging pipeline does it: the grids' raw bytes as
// images (unknown 255, free 0, occupied 100), AKAZE features, AffineBestOf2NearestMatcher,
// leaveBiggestComponent at a confidence of 0.6 (its default), AffineBasedEstimator, then
// BundleAdjusterAffinePartial; the resulting similarity between the images becomes a_from_b in
// the map frames (its scale dropped, as a rigid transform).
//
// A pure function of its inputs; OpenCV's own thread pool is the caller's to size.

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct MexploreOptions {
  // m-explore's estimation_confidence: pairs whose match confidence is below it are dropped.
  double confidence = 0.6;
};

struct MexploreRegistration {
  bool found = false;  // both grids stayed in the biggest component and the estimation held
  Pose2 a_from_b;      // when found: p_a = a_from_b * p_b
  double match_confidence = 0.0;  // OpenCV's pairwise match confidence (inliers vs matches)
  double scale = 1.0;  // the scale of the estimated similarity (1 for a perfect estimate)
};

MexploreRegistration RegisterLikeMexplore(const grid::OccupancyGrid& a,
                                          const grid::OccupancyGrid& b,
                                          const MexploreOptions& options = {});

}  // namespace fleetmap::bench
