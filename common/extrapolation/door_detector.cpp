#include "common/extrapolation/door_detector.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "common/extrapolation/patch_image.hpp"
#include "common/extrapolation/ransac_plane.hpp"
#include "common/extrapolation/voxel_filter.hpp"

namespace fleetmap::extrapolation {
namespace {

// Splits a plane patch into runs of dense columns (cells of image_cell along s): a door leaf
// fills its columns from the floor to its top, while the sparse band where a neighbouring wall
// face grazes the plane does not. Each run's points, in index order.
std::vector<std::vector<int>> DenseRuns(const std::vector<Point2>& image_points,
                                        const std::vector<int>& component,
                                        const DoorDetectorOptions& options) {
  double s_min = image_points[component[0]].x(), s_max = s_min;
  for (int k : component) {
    s_min = std::min(s_min, image_points[k].x());
    s_max = std::max(s_max, image_points[k].x());
  }
  const double cell = options.image_cell;
  const int columns = std::min(100000, static_cast<int>((s_max - s_min) / cell) + 1);
  const int rows = static_cast<int>(options.max_height / cell) + 1;
  std::vector<std::vector<uint8_t>> filled(columns, std::vector<uint8_t>(rows, 0));
  for (int k : component) {
    const int c = std::min(columns - 1, static_cast<int>((image_points[k].x() - s_min) / cell));
    const int r = static_cast<int>(image_points[k].y() / cell);
    if (r >= 0 && r < rows) filled[c][r] = 1;
  }
  const double needed = options.min_fill * options.min_height / cell;
  std::vector<uint8_t> dense(columns, 0);
  for (int c = 0; c < columns; ++c) {
    int count = 0;
    for (uint8_t f : filled[c]) count += f;
    dense[c] = count >= needed;
  }
  std::vector<std::vector<int>> runs;
  for (int c = 0; c < columns;) {
    if (!dense[c]) {
      ++c;
      continue;
    }
    int end = c;
    while (end + 1 < columns && dense[end + 1]) ++end;
    const double lo = s_min + c * cell, hi = s_min + (end + 1) * cell;
    std::vector<int> run;
    for (int k : component) {
      if (image_points[k].x() >= lo && image_points[k].x() < hi) run.push_back(k);
    }
    runs.push_back(std::move(run));
    c = end + 1;
  }
  return runs;
}

}  // namespace

std::vector<DetectedDoor> DetectDoors(const PointCloud& cloud,
                                      const std::optional<Point2>& viewpoint,
                                      const DoorDetectorOptions& options) {
  std::vector<DetectedDoor> found;
  const PointCloud all = VoxelFilter(cloud, options.voxel_size);
  PointCloud remaining;
  for (const Point3& p : all) {
    if (p.z() > 0.5 * options.floor_tolerance) remaining.push_back(p);
  }
  for (int attempt = 0; attempt < options.max_planes; ++attempt) {
    RansacOptions ransac;
    ransac.distance_threshold = options.plane_threshold;
    ransac.iterations = options.iterations;
    ransac.min_inliers = options.min_plane_points;
    ransac.min_tilt = 0.5 * std::numbers::pi - options.max_tilt_error;
    ransac.seed = options.seed + static_cast<uint32_t>(attempt);
    const std::optional<PlaneFit> fit = FitPlaneRansac(remaining, ransac);
    if (!fit) break;
    const Plane& plane = fit->plane;
    const Vector2 normal = Vector2(plane.normal.x(), plane.normal.y()).normalized();
    const Vector2 along(-normal.y(), normal.x());
    const double offset = -plane.offset;  // n . p = offset on the plane
    std::vector<Point2> image_points;     // (s along the plane, z)
    for (int i : fit->inliers) {
      const Point3& p = remaining[i];
      image_points.push_back(Point2(along.dot(Vector2(p.x(), p.y())), p.z()));
    }
    const PatchImage image(image_points, options.image_cell);
    for (const std::vector<int>& component : image.Components()) {
      if (static_cast<int>(component.size()) < options.min_plane_points / 3) break;
      for (const std::vector<int>& patch : DenseRuns(image_points, component, options)) {
        std::vector<double> s, z;
        for (int k : patch) {
          s.push_back(image_points[k].x());
          z.push_back(image_points[k].y());
        }
        const double s0 = Percentile(s, 0.005), s1 = Percentile(s, 0.995);
        const double z0 = Percentile(z, 0.005), z1 = Percentile(z, 0.995);
        const double width = s1 - s0, height = z1;
        if (width < options.min_width || width > options.max_width) continue;
        if (height < options.min_height || height > options.max_height) continue;
        if (z0 > options.floor_tolerance) continue;
        const double cells =
            std::max(1.0, (width / options.image_cell) * (height / options.image_cell));
        if (image.CellCount(patch) < options.min_fill * cells) continue;
        // The four corners: at the floor and at the door's height, on both edges.
        const int r = std::max(
            1, static_cast<int>(std::lround(options.corner_tolerance / options.image_cell)));
        const double zb = std::max(z0, 0.5 * options.floor_tolerance) + options.image_cell;
        if (!image.Occupied(Point2(s0, zb), r) || !image.Occupied(Point2(s1, zb), r) ||
            !image.Occupied(Point2(s0, z1), r) || !image.Occupied(Point2(s1, z1), r)) {
          continue;
        }
        // A door sits in a wall: wall points beside both vertical edges, near the leaf's plane
        // (an open leaf standing in a room, or a cabinet, has none on one side at least).
        if (options.min_wall_points > 0) {
          int wall_s0 = 0, wall_s1 = 0;
          for (const Point3& p : all) {
            const double d = std::abs(normal.dot(Vector2(p.x(), p.y())) - offset);
            if (d > options.wall_max_offset || p.z() < 0.3 || p.z() > options.min_height) continue;
            const double ps = along.dot(Vector2(p.x(), p.y()));
            wall_s0 += ps < s0 - 0.05 && ps > s0 - options.wall_search;
            wall_s1 += ps > s1 + 0.05 && ps < s1 + options.wall_search;
          }
          if (wall_s0 < options.min_wall_points || wall_s1 < options.min_wall_points) continue;
        }
        // The handle: points just off the leaf, at handle height, near either vertical edge.
        int near_s0 = 0, near_s1 = 0;
        const double margin = options.voxel_size;
        for (const Point3& p : all) {
          const double d = std::abs(normal.dot(Vector2(p.x(), p.y())) - offset);
          if (d < options.handle_min_offset || d > options.handle_max_offset) continue;
          if (p.z() < options.handle_min_z || p.z() > options.handle_max_z) continue;
          const double ps = along.dot(Vector2(p.x(), p.y()));
          if (ps > s0 + margin && ps < s0 + options.handle_edge_band) ++near_s0;
          if (ps < s1 - margin && ps > s1 - options.handle_edge_band) ++near_s1;
        }
        const Point2 on_plane = offset * normal;
        const Point2 edge0 = on_plane + s0 * along, edge1 = on_plane + s1 * along;
        DetectedDoor door;
        door.entity.id = "door_" + std::to_string(found.size() + 1);
        const bool latch_at_s0 = near_s0 > near_s1;
        door.entity.latch = latch_at_s0 ? edge0 : edge1;
        door.entity.hinge = latch_at_s0 ? edge1 : edge0;
        door.handle_points_latch = std::max(near_s0, near_s1);
        door.handle_points_hinge = std::min(near_s0, near_s1);
        door.height = height;
        door.entity.open = false;
        Vector2 opening = normal;
        if (viewpoint && opening.dot(door.entity.center() - *viewpoint) < 0.0) opening = -opening;
        door.entity.opening_direction = viewpoint ? opening : Vector2::Zero();
        found.push_back(door);
      }
    }
    remaining = WithoutInliers(remaining, fit->inliers);
  }
  return found;
}

}  // namespace fleetmap::extrapolation
