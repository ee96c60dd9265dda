#include "common/extrapolation/voxel_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fleetmap::extrapolation {

PointCloud VoxelFilter(const PointCloud& cloud, double voxel_size) {
  using Key = std::array<int64_t, 3>;
  std::vector<std::pair<Key, int>> keyed;
  keyed.reserve(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Point3& p = cloud[i];
    if (!p.allFinite()) continue;
    keyed.push_back({{static_cast<int64_t>(std::floor(p.x() / voxel_size)),
                      static_cast<int64_t>(std::floor(p.y() / voxel_size)),
                      static_cast<int64_t>(std::floor(p.z() / voxel_size))},
                     static_cast<int>(i)});
  }
  std::sort(keyed.begin(), keyed.end());
  PointCloud out;
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i;
    Point3 sum = Point3::Zero();
    while (j < keyed.size() && keyed[j].first == keyed[i].first) sum += cloud[keyed[j++].second];
    out.push_back(sum / static_cast<double>(j - i));
    i = j;
  }
  return out;
}

}  // namespace fleetmap::extrapolation
