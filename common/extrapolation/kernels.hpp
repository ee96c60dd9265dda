#pragma once

// The extrapolation kernels of ALGORITHMS.md 3, peak-normalised: each returns a confidence in
// [0, 1] that is 1 at the kernel's mode, so a threshold p_th means the same for any sigma.
//
// Skew-normal (Azzalini): f(u) = 2 phi_Omega(u) Phi(alpha^T omega^-1 u), Omega = diag(sx^2, sy^2),
// omega = diag(sx, sy), phi the zero-mean normal density, Phi the standard normal CDF. The mass
// moves towards +alpha; alpha = 0 is the normal.
//
// Thread-safety: immutable after construction.

#include "common/core/types.hpp"

namespace fleetmap::extrapolation {

// Standard normal CDF.
double NormalCdf(double x);

// exp(-|u|^2 / (2 sigma^2)): N(0, sigma^2 I) divided by its peak.
double NormalizedGaussian(const Vector2& u, double sigma);

class SkewNormalKernel {
 public:
  // sigma_x, sigma_y > 0 (metres), alpha dimensionless, in the kernel's frame.
  SkewNormalKernel(double sigma_x, double sigma_y, const Vector2& alpha);

  // The density f(u) (u in the kernel's frame, metres).
  double Density(const Vector2& u) const;
  // f(u) / f(mode), in [0, 1].
  double Normalized(const Vector2& u) const { return Density(u) / peak_; }
  // Where f is largest, and its value there.
  const Vector2& mode() const { return mode_; }
  double peak() const { return peak_; }
  // A radius (metres, from the origin) outside which Normalized < p_th: bounds the cells to
  // evaluate.
  double SupportRadius(double p_th) const;

 private:
  double sigma_x_;
  double sigma_y_;
  Vector2 alpha_;
  Vector2 mode_ = Vector2::Zero();
  double peak_ = 1.0;
};

}  // namespace fleetmap::extrapolation
