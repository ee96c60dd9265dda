#pragma once

// A simulated RGB-D depth camera (Asus Xtion / RealSense class): a pinhole camera that ray-casts
// every pixel against upright boxes and the floor plane z = 0, and returns noisy 3D points in the
// map frame. Range noise grows with the square of the distance, as structured-light and stereo
// sensors' does (sigma = a + b (d - 0.4)^2, after Khoshelham and Elberink 2012); a few pixels drop
// out. Everything random comes from the caller's Random, so a seed gives the same cloud.
//
// Thread-safety: a DepthSensor is immutable; Capture() is safe to call concurrently with
// different Random objects.

#include <vector>

#include <Eigen/Core>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/sim/indoor_scene.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::sim {

struct DepthSensorOptions {
  int columns = 240;                                        // >= 1
  int rows = 160;                                           // >= 1
  double horizontal_fov = 87.0 * 3.14159265358979 / 180.0;  // radians, in (0, pi)
  double vertical_fov = 58.0 * 3.14159265358979 / 180.0;    // radians, in (0, pi)
  double min_range = 0.3;                                   // metres
  double max_range = 6.0;                                   // metres, > min_range
  double noise_a = 0.0012;                                  // metres
  double noise_b = 0.0019;                                  // 1 / metres
  double dropout_probability = 0.01;
};

// Where the camera is: its planar pose in the map frame, its height above the floor and its
// pitch (radians, positive looks up).
struct CameraPose {
  Pose2 pose;
  double height = 1.0;
  double pitch = 0.0;
};

class DepthSensor {
 public:
  // Errors (kInvalidArgument) name the option.
  static StatusOr<DepthSensor> Create(const DepthSensorOptions& options);

  const DepthSensorOptions& options() const { return options_; }

  // The points the camera sees (map frame, metres), row by row.
  std::vector<Eigen::Vector3d> Capture(const std::vector<Box3>& boxes, const CameraPose& camera,
                                       Random* random) const;

  // The noiseless distance along a map-frame ray to the first box or the floor, or +infinity.
  static double CastRay(const std::vector<Box3>& boxes, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction);

 private:
  explicit DepthSensor(const DepthSensorOptions& options) : options_(options) {}

  DepthSensorOptions options_;
};

}  // namespace fleetmap::sim
