#include "common/extrapolation/stairs_detector.hpp"

#include <algorithm>
#include <cmath>

#include "common/extrapolation/patch_image.hpp"
#include "common/extrapolation/ransac_plane.hpp"
#include "common/extrapolation/voxel_filter.hpp"

namespace fleetmap::extrapolation {
std::vector<DetectedStairs> DetectStairs(const PointCloud& cloud,
                                         const StairsDetectorOptions& options) {
  std::vector<DetectedStairs> found;
  PointCloud remaining;
  for (const Point3& p : VoxelFilter(cloud, options.voxel_size)) {
    if (p.z() >= options.floor_clearance) remaining.push_back(p);
  }
  const Vector3 z = Vector3::UnitZ();
  const int min_inliers = std::max(
      20, static_cast<int>(0.5 * options.min_area / (options.voxel_size * options.voxel_size)));
  for (int attempt = 0;
       attempt < options.max_attempts && static_cast<int>(found.size()) < options.max_flights;
       ++attempt) {
    RansacOptions ransac;
    ransac.distance_threshold = options.plane_threshold;
    ransac.iterations = options.iterations;
    ransac.min_inliers = min_inliers;
    ransac.min_tilt = options.min_tilt;
    ransac.max_tilt = options.max_tilt;
    ransac.seed = options.seed + static_cast<uint32_t>(attempt);
    const std::optional<PlaneFit> fit = FitPlaneRansac(remaining, ransac);
    if (!fit) break;
    const Vector3 n = fit->plane.normal;  // n_z > 0
    const Vector3 w = n.cross(z).cross(n);
    const Vector3 o = (w.dot(z) >= 0.0 ? w : Vector3(-w)).normalized();  // up the slope
    const Vector2 up = Vector2(o.x(), o.y()).normalized();
    const Vector2 across(-up.y(), up.x());
    // The inliers in the plane: along the slope and across the flight.
    std::vector<Point2> coordinates;
    for (int i : fit->inliers) {
      const Point3& p = remaining[i];
      coordinates.push_back(Point2(p.dot(o), across.dot(Vector2(p.x(), p.y()))));
    }
    const PatchImage image(coordinates, options.patch_cell);
    const std::vector<std::vector<int>> components = image.Components();
    if (!components.empty()) {
      const std::vector<int>& patch = components.front();
      std::vector<double> along, side, height, horizontal;
      for (int k : patch) {
        along.push_back(coordinates[k].x());
        side.push_back(coordinates[k].y());
        const Point3& p = remaining[fit->inliers[k]];
        height.push_back(p.z());
        horizontal.push_back(up.dot(Vector2(p.x(), p.y())));
      }
      const double area = image.CellCount(patch) * options.patch_cell * options.patch_cell;
      const double side_lo = Percentile(side, 0.02), side_hi = Percentile(side, 0.98);
      const double length = Percentile(along, 0.98) - Percentile(along, 0.02);
      const double width = side_hi - side_lo;
      if (area >= options.min_area && width >= options.min_width && length >= options.min_length &&
          area >= options.min_fill * width * length) {
        const double pitch = std::atan2(std::abs(o.z()), Vector2(o.x(), o.y()).norm());
        // The foot: the lowest riser seen, along the ascending direction.
        std::vector<double> low;
        const double z_low = Percentile(height, 0.02);
        for (size_t k = 0; k < patch.size(); ++k) {
          if (height[k] <= z_low + 0.15) low.push_back(horizontal[k]);
        }
        const double foot_along = Percentile(low, 0.1);
        const double side_mid = 0.5 * (side_lo + side_hi);
        DetectedStairs stairs;
        stairs.entity.id = "stairs_" + std::to_string(found.size() + 1);
        stairs.entity.position = foot_along * up + side_mid * across;
        stairs.entity.ascending = up;
        stairs.entity.step_width = width;
        stairs.entity.next_floor_height =
            std::max(options.expected_floor_height, Percentile(height, 0.99));
        stairs.entity.run_length =
            std::max(0.0, stairs.entity.next_floor_height - options.riser_height) / std::tan(pitch);
        stairs.area = area;
        stairs.inliers = static_cast<int>(patch.size());
        found.push_back(stairs);
      }
    }
    // Drop the plane's inliers (accepted or not) and look for the next plane.
    remaining = WithoutInliers(remaining, fit->inliers);
  }
  return found;
}

}  // namespace fleetmap::extrapolation
