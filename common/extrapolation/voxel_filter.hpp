#pragma once

// Voxel-grid down-sampling: one point per occupied cubic voxel (the centroid of its points).
// Output order is deterministic (sorted by voxel index).
//
// Thread-safety: stateless.

#include "common/extrapolation/point_cloud.hpp"

namespace fleetmap::extrapolation {

// `voxel_size` > 0 metres; non-finite points are dropped.
PointCloud VoxelFilter(const PointCloud& cloud, double voxel_size);

}  // namespace fleetmap::extrapolation
