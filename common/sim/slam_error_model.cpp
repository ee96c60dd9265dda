#include "common/sim/slam_error_model.hpp"

#include <cmath>

namespace fleetmap::sim {
namespace {

bool NonNegative(double v) { return v >= 0.0 && std::isfinite(v); }

}  // namespace

StatusOr<SlamErrorModel> SlamErrorModel::Create(const SlamErrorOptions& options, uint32_t seed) {
  if (!NonNegative(options.jitter_xy) || !NonNegative(options.jitter_yaw)) {
    return InvalidArgumentError("error model jitter_xy and jitter_yaw must be finite and >= 0");
  }
  if (!NonNegative(options.drift_xy) || !NonNegative(options.drift_yaw)) {
    return InvalidArgumentError("error model drift_xy and drift_yaw must be finite and >= 0");
  }
  if (!std::isfinite(options.correction_length)) {
    return InvalidArgumentError("error model correction_length must be finite");
  }
  return SlamErrorModel(options, seed);
}

void SlamErrorModel::Advance(double distance) {
  if (!options_.enabled || !(distance > 0.0)) return;
  const double keep =
      options_.correction_length > 0.0 ? std::exp(-distance / options_.correction_length) : 1.0;
  const double root = std::sqrt(distance);
  drift_.x = drift_.x * keep + random_.Gaussian(0.0, options_.drift_xy * root);
  drift_.y = drift_.y * keep + random_.Gaussian(0.0, options_.drift_xy * root);
  drift_.yaw = drift_.yaw * keep + random_.Gaussian(0.0, options_.drift_yaw * root);
}

Pose2 SlamErrorModel::Belief(const Pose2& truth) {
  if (!options_.enabled) return truth;
  return {truth.x + drift_.x + random_.Gaussian(0.0, options_.jitter_xy),
          truth.y + drift_.y + random_.Gaussian(0.0, options_.jitter_xy),
          NormalizeAngle(truth.yaw + drift_.yaw + random_.Gaussian(0.0, options_.jitter_yaw))};
}

}  // namespace fleetmap::sim
