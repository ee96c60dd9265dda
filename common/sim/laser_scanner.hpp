#pragma once

// A simulated 2D laser range finder, ray-cast on the ground-truth grid. Defaults are a SICK
// LMS200-class scanner as mounted on a Pioneer 3-DX: 180 degrees, 1 degree steps (181 rays),
// 30 m useful range on office walls, 1 cm Gaussian range noise.
//
// Ray casting walks the cells of the truth grid along the beam (Amanatides-Woo traversal) and
// returns the distance at which the beam enters the first occupied cell, plus noise. Beams that
// reach max_range without a hit return kNoReturn.
//
// Thread-safety: a LaserScanner is immutable; Scan() is safe to call concurrently with different
// Random objects.

#include <limits>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::sim {

struct LaserOptions {
  double field_of_view = 3.14159265358979323846;         // radians, in (0, 2 pi]
  double angular_step = 3.14159265358979323846 / 180.0;  // radians, > 0
  double max_range = 30.0;                               // metres, > min_range
  double min_range = 0.05;                               // metres, >= 0
  double range_noise_stddev = 0.01;                      // metres, >= 0
  // Probability that a beam returns a spurious short range (dust, a reflection): speckle in maps.
  double outlier_probability = 0.001;  // in [0, 1]
};

inline constexpr float kNoReturn = std::numeric_limits<float>::infinity();

// One sweep, angles relative to the sensor's heading, counter-clockwise, like
// sensor_msgs/LaserScan.
struct LaserScan {
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double max_range = 0.0;
  std::vector<float> ranges;  // metres, or kNoReturn
};

class LaserScanner {
 public:
  // Errors (kInvalidArgument) name the option: no rays (field_of_view or angular_step <= 0),
  // bad ranges, noise or outlier probability.
  static StatusOr<LaserScanner> Create(const LaserOptions& options);

  const LaserOptions& options() const { return options_; }
  int ray_count() const { return ray_count_; }

  // A scan from `map_from_sensor` in the truth grid (occupied cells stop the beam). The grid's
  // origin must have yaw 0.
  LaserScan Scan(const grid::OccupancyGrid& truth, const Pose2& map_from_sensor,
                 Random* random) const;

  // The noiseless distance (metres) from `origin` along `angle` (map frame) to the first occupied
  // cell, or kNoReturn within max_range. Exposed for tests.
  float CastRay(const grid::OccupancyGrid& truth, const Point2& origin, double angle) const;

 private:
  LaserScanner(const LaserOptions& options, int ray_count)
      : options_(options), ray_count_(ray_count) {}

  LaserOptions options_;
  int ray_count_ = 0;
};

}  // namespace fleetmap::sim
