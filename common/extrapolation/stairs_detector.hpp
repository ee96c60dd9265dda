#pragma once

// Finds flights of stairs in a 3D point cloud (ALGORITHMS.md 3, static entities): voxel filter,
// drop the floor, RANSAC for planes tilted about 45 degrees (the steps' nosings and risers lie
// within a few centimetres of one inclined plane), keep the largest connected patch of inliers and
// accept it if its area and its extents across and along the flight are large enough. With n the
// patch normal and z vertical, w = (n x z) x n and the ascending direction o = w sgn(w^T z).
// The foot is the lowest riser seen, the step width the patch's extent across the flight, and the
// run from the foot to the top edge (next_floor_height - riser_height) / tan(pitch), the pitch
// being the patch's.
//
// Thread-safety: stateless.

#include <string>
#include <vector>

#include "common/extrapolation/point_cloud.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

struct StairsDetectorOptions {
  double voxel_size = 0.04;
  double floor_clearance = 0.06;  // points below this height are floor
  double plane_threshold = 0.09;  // inclined-plane band half-width (the step sawtooth fits in)
  double min_tilt = 0.35;         // radians (20 deg)
  double max_tilt = 1.05;         // radians (60 deg)
  double min_area = 0.8;          // m^2 of the inclined patch
  double min_width = 0.5;         // m across the flight
  double min_length = 0.6;        // m along the slope
  // Area over (width x length): a band where a tilted plane cuts walls is long and thin, or an L.
  double min_fill = 0.5;
  double patch_cell = 0.1;  // m: connectivity grid on the plane
  // The floor height assumed at the top when the sensor does not see that high (the paper's
  // "expected height of the new floor"); a patch reaching higher sets it instead.
  double expected_floor_height = 3.0;
  // The last riser lifts onto the upper floor: the top edge is one riser below the floor height
  // on the patch's slope, run = (next_floor_height - riser_height) / tan(pitch).
  double riser_height = 0.17;
  int iterations = 400;
  int max_flights = 3;
  int max_attempts = 8;  // planes tried (rejected patches included)
  uint32_t seed = 7;
};

struct DetectedStairs {
  scene::StairsEntity entity;
  double area = 0;  // m^2 of the patch
  int inliers = 0;
};

// Ids are "stairs_<k>" in detection order.
std::vector<DetectedStairs> DetectStairs(const PointCloud& cloud,
                                         const StairsDetectorOptions& options = {});

}  // namespace fleetmap::extrapolation
