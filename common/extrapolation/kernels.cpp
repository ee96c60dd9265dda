#include "common/extrapolation/kernels.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/core/check.hpp"

namespace fleetmap::extrapolation {

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

double NormalizedGaussian(const Vector2& u, double sigma) {
  return std::exp(-u.squaredNorm() / (2.0 * sigma * sigma));
}

SkewNormalKernel::SkewNormalKernel(double sigma_x, double sigma_y, const Vector2& alpha)
    : sigma_x_(sigma_x), sigma_y_(sigma_y), alpha_(alpha) {
  FLEETMAP_CHECK(sigma_x > 0.0 && sigma_y > 0.0);
  // In standardised coordinates z = omega^-1 u the density is 2 phi(z) Phi(alpha^T z), whose mode
  // lies on the ray along alpha: maximise g(t) = phi(t) Phi(|alpha| t) over t >= 0 by golden
  // section (g is unimodal there).
  const double a = alpha_.norm();
  Vector2 z_mode = Vector2::Zero();
  if (a > 0.0) {
    auto g = [a](double t) { return -0.5 * t * t + std::log(std::max(1e-300, NormalCdf(a * t))); };
    double lo = 0.0, hi = 3.0;
    const double r = (std::sqrt(5.0) - 1.0) / 2.0;
    double c = hi - r * (hi - lo), d = lo + r * (hi - lo);
    for (int i = 0; i < 100; ++i) {
      if (g(c) > g(d)) {
        hi = d;
      } else {
        lo = c;
      }
      c = hi - r * (hi - lo);
      d = lo + r * (hi - lo);
    }
    z_mode = alpha_ / a * (0.5 * (lo + hi));
  }
  mode_ = Vector2(z_mode.x() * sigma_x_, z_mode.y() * sigma_y_);
  peak_ = Density(mode_);
}

double SkewNormalKernel::Density(const Vector2& u) const {
  const Vector2 z(u.x() / sigma_x_, u.y() / sigma_y_);
  const double phi =
      std::exp(-0.5 * z.squaredNorm()) / (2.0 * std::numbers::pi * sigma_x_ * sigma_y_);
  return 2.0 * phi * NormalCdf(alpha_.dot(z));
}

double SkewNormalKernel::SupportRadius(double p_th) const {
  // Normalized(u) <= 2 phi(u) / peak (Phi <= 1): outside the ellipse where that bound drops
  // below p_th the kernel does too. Solve exp(-|z|^2 / 2) <= p_th * peak / (2 phi(0)).
  const double phi0 = 1.0 / (2.0 * std::numbers::pi * sigma_x_ * sigma_y_);
  const double ratio = std::clamp(p_th * peak_ / (2.0 * phi0), 1e-12, 1.0);
  const double z = std::sqrt(-2.0 * std::log(ratio));
  return z * std::max(sigma_x_, sigma_y_);
}

}  // namespace fleetmap::extrapolation
