#include "common/vector_map/lattice.hpp"

#include <cmath>
#include <numbers>

namespace fleetmap::vector_map {

double Lattice::MaxDisplacement() const {
  return enabled() ? quantum_ * std::numbers::sqrt2 / 2.0 : 0.0;
}

Point2 Lattice::Snap(const Point2& p) const {
  if (!enabled()) return p;
  const double kx = std::round((p.x() - origin_.x()) / quantum_);
  const double ky = std::round((p.y() - origin_.y()) / quantum_);
  return Point2(origin_.x() + kx * quantum_, origin_.y() + ky * quantum_);
}

bool Lattice::Contains(const Point2& p) const {
  if (!enabled()) return true;
  const double kx = (p.x() - origin_.x()) / quantum_;
  const double ky = (p.y() - origin_.y()) / quantum_;
  constexpr double kTolerance = 1e-6;
  return std::abs(kx - std::round(kx)) < kTolerance && std::abs(ky - std::round(ky)) < kTolerance;
}

}  // namespace fleetmap::vector_map
