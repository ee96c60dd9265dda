#include "common/sim/depth_sensor.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace fleetmap::sim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Slab test of a ray against one upright box; the entry distance or +infinity.
double IntersectBox(const Box3& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const double ox = origin.x() - box.center.x(), oy = origin.y() - box.center.y();
  const double o[3] = {c * ox + s * oy, -s * ox + c * oy, origin.z()};
  const double d[3] = {c * dir.x() + s * dir.y(), -s * dir.x() + c * dir.y(), dir.z()};
  const double lo[3] = {-box.half_length, -box.half_width, box.z_min};
  const double hi[3] = {box.half_length, box.half_width, box.z_max};
  double t_near = 0.0, t_far = kInfinity;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(d[axis]) < 1e-12) {
      if (o[axis] < lo[axis] || o[axis] > hi[axis]) return kInfinity;
      continue;
    }
    double t0 = (lo[axis] - o[axis]) / d[axis], t1 = (hi[axis] - o[axis]) / d[axis];
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
    if (t_near > t_far) return kInfinity;
  }
  return t_near > 0.0 ? t_near : kInfinity;
}

}  // namespace

StatusOr<DepthSensor> DepthSensor::Create(const DepthSensorOptions& o) {
  if (o.columns < 1 || o.rows < 1)
    return InvalidArgumentError("depth sensor: columns and rows must be >= 1");
  if (!(o.horizontal_fov > 0.0 && o.horizontal_fov < std::numbers::pi) ||
      !(o.vertical_fov > 0.0 && o.vertical_fov < std::numbers::pi)) {
    return InvalidArgumentError("depth sensor: fields of view must be in (0, pi)");
  }
  if (!(o.min_range >= 0.0 && o.max_range > o.min_range && std::isfinite(o.max_range))) {
    return InvalidArgumentError("depth sensor: need 0 <= min_range < max_range");
  }
  if (!(o.noise_a >= 0.0 && o.noise_b >= 0.0) ||
      !(o.dropout_probability >= 0.0 && o.dropout_probability <= 1.0)) {
    return InvalidArgumentError("depth sensor: bad noise or dropout probability");
  }
  return DepthSensor(o);
}

double DepthSensor::CastRay(const std::vector<Box3>& boxes, const Eigen::Vector3d& origin,
                            const Eigen::Vector3d& direction) {
  double best = direction.z() < 0.0 ? -origin.z() / direction.z() : kInfinity;  // the floor
  for (const Box3& box : boxes) best = std::min(best, IntersectBox(box, origin, direction));
  return best;
}

std::vector<Eigen::Vector3d> DepthSensor::Capture(const std::vector<Box3>& boxes,
                                                  const CameraPose& camera, Random* random) const {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d origin(camera.pose.x, camera.pose.y, camera.height);
  const double fx = std::tan(0.5 * options_.horizontal_fov);
  const double fy = std::tan(0.5 * options_.vertical_fov);
  const double cy = std::cos(camera.pose.yaw), sy = std::sin(camera.pose.yaw);
  const double cp = std::cos(camera.pitch), sp = std::sin(camera.pitch);
  // Camera axes in the map frame: forward, left, up (pitched about the left axis).
  const Eigen::Vector3d forward(cy * cp, sy * cp, sp);
  const Eigen::Vector3d left(-sy, cy, 0.0);
  const Eigen::Vector3d up(-cy * sp, -sy * sp, cp);
  for (int r = 0; r < options_.rows; ++r) {
    const double v = fy * (1.0 - 2.0 * (r + 0.5) / options_.rows);
    for (int c = 0; c < options_.columns; ++c) {
      const double u = fx * (1.0 - 2.0 * (c + 0.5) / options_.columns);
      const Eigen::Vector3d direction = (forward + u * left + v * up).normalized();
      const double range = CastRay(boxes, origin, direction);
      const bool dropped = random->Bernoulli(options_.dropout_probability);
      if (!(range >= options_.min_range && range <= options_.max_range) || dropped) continue;
      const double sigma = options_.noise_a + options_.noise_b * (range - 0.4) * (range - 0.4);
      points.push_back(origin + (range + random->Gaussian(0.0, sigma)) * direction);
    }
  }
  return points;
}

}  // namespace fleetmap::sim
