#include "common/sim/laser_scanner.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace fleetmap::sim {

StatusOr<LaserScanner> LaserScanner::Create(const LaserOptions& options) {
  if (!(options.field_of_view > 0.0 && options.field_of_view <= 2.0 * std::numbers::pi + 1e-9)) {
    return InvalidArgumentError(
        "laser field_of_view must be in (0, 2 pi] rad: a laser with no rays");
  }
  if (!(options.angular_step > 0.0) || !std::isfinite(options.angular_step)) {
    return InvalidArgumentError("laser angular_step must be > 0 rad: a laser with no rays");
  }
  if (!(options.min_range >= 0.0) || !(options.max_range > options.min_range) ||
      !std::isfinite(options.max_range)) {
    return InvalidArgumentError("laser max_range must be finite and above min_range >= 0");
  }
  if (!(options.range_noise_stddev >= 0.0) || !std::isfinite(options.range_noise_stddev)) {
    return InvalidArgumentError("laser range_noise_stddev must be >= 0");
  }
  if (!(options.outlier_probability >= 0.0 && options.outlier_probability <= 1.0)) {
    return InvalidArgumentError("laser outlier_probability must be in [0, 1]");
  }
  const double rays = std::floor(options.field_of_view / options.angular_step + 1e-9) + 1.0;
  if (rays > 100000.0) {
    return InvalidArgumentError("laser angular_step gives more than 100000 rays");
  }
  return LaserScanner(options, static_cast<int>(rays));
}

float LaserScanner::CastRay(const grid::OccupancyGrid& truth, const Point2& origin,
                            double angle) const {
  const double res = truth.resolution();
  // Grid coordinates in cells.
  const double gx = (origin.x() - truth.origin().x) / res;
  const double gy = (origin.y() - truth.origin().y) / res;
  const double dx = std::cos(angle);
  const double dy = std::sin(angle);
  int cx = static_cast<int>(std::floor(gx));
  int cy = static_cast<int>(std::floor(gy));
  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  constexpr double kHuge = 1e30;
  // Parameter t in cells along the beam at which the next x / y cell border is crossed.
  const double delta_x = dx != 0.0 ? std::abs(1.0 / dx) : kHuge;
  const double delta_y = dy != 0.0 ? std::abs(1.0 / dy) : kHuge;
  double next_x = dx != 0.0 ? ((dx > 0.0 ? (cx + 1 - gx) : (gx - cx)) * delta_x) : kHuge;
  double next_y = dy != 0.0 ? ((dy > 0.0 ? (cy + 1 - gy) : (gy - cy)) * delta_y) : kHuge;
  const double max_t = options_.max_range / res;
  const int width = truth.width();
  const int height = truth.height();
  const int8_t* cells = truth.data().data();
  double t = 0.0;
  while (t <= max_t) {
    if (cx < 0 || cy < 0 || cx >= width || cy >= height) return kNoReturn;
    if (cells[static_cast<size_t>(cy) * width + cx] >= grid::kOccupiedValue / 2) {
      return static_cast<float>(t * res);
    }
    if (next_x < next_y) {
      t = next_x;
      next_x += delta_x;
      cx += step_x;
    } else {
      t = next_y;
      next_y += delta_y;
      cy += step_y;
    }
  }
  return kNoReturn;
}

LaserScan LaserScanner::Scan(const grid::OccupancyGrid& truth, const Pose2& map_from_sensor,
                             Random* random) const {
  LaserScan scan;
  scan.angle_min = -options_.field_of_view / 2.0;
  scan.angle_increment = options_.angular_step;
  scan.max_range = options_.max_range;
  scan.ranges.resize(ray_count_);
  const Point2 origin = map_from_sensor.translation();
  for (int i = 0; i < ray_count_; ++i) {
    const double angle = map_from_sensor.yaw + scan.angle_min + i * scan.angle_increment;
    float range = CastRay(truth, origin, angle);
    // Always draw the same number of deviates per beam, so one beam's outcome does not shift the
    // random stream of the next.
    const double noise = random->Gaussian(0.0, options_.range_noise_stddev);
    const double outlier = random->Uniform();
    const double outlier_fraction = random->Uniform();
    if (range != kNoReturn) {
      range = static_cast<float>(std::max(options_.min_range, range + noise));
      if (range > options_.max_range) range = kNoReturn;
    }
    if (outlier < options_.outlier_probability) {
      const double limit = range == kNoReturn ? options_.max_range : range;
      range =
          static_cast<float>(options_.min_range + outlier_fraction * (limit - options_.min_range));
    }
    scan.ranges[i] = range;
  }
  return scan;
}

}  // namespace fleetmap::sim
