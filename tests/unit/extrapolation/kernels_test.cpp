#include "common/extrapolation/kernels.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::extrapolation {
namespace {

TEST(KernelsTest, NormalCdfKnownValues) {
  EXPECT_NEAR(NormalCdf(0.0), 0.5, 1e-12);
  EXPECT_NEAR(NormalCdf(1.0), 0.841344746, 1e-8);
  EXPECT_NEAR(NormalCdf(-1.96), 0.0249979, 1e-6);
}

TEST(KernelsTest, NormalizedGaussianPeaksAtOneAndHalvesAtKnownRadius) {
  EXPECT_DOUBLE_EQ(NormalizedGaussian(Vector2::Zero(), 0.7), 1.0);
  const double r = 0.7 * std::sqrt(2.0 * std::log(2.0));
  EXPECT_NEAR(NormalizedGaussian(Vector2(r, 0.0), 0.7), 0.5, 1e-12);
  EXPECT_NEAR(NormalizedGaussian(Vector2(0.0, -r), 0.7), 0.5, 1e-12);
}

TEST(KernelsTest, SkewNormalIsPeakNormalised) {
  const SkewNormalKernel kernel(1.0, 0.5, Vector2(0.0, 3.0));
  double best = 0.0;
  for (double x = -3.0; x <= 3.0; x += 0.01) {
    for (double y = -3.0; y <= 3.0; y += 0.01) {
      const double v = kernel.Normalized(Vector2(x, y));
      EXPECT_LE(v, 1.0 + 1e-9);
      best = std::max(best, v);
    }
  }
  EXPECT_NEAR(best, 1.0, 1e-3);
  EXPECT_NEAR(kernel.Normalized(kernel.mode()), 1.0, 1e-12);
}

TEST(KernelsTest, SkewNormalLeansTowardsAlpha) {
  const SkewNormalKernel kernel(1.0, 1.0, Vector2(0.0, 3.0));
  // The mode moves along +alpha (y), not sideways.
  EXPECT_GT(kernel.mode().y(), 0.3);
  EXPECT_NEAR(kernel.mode().x(), 0.0, 1e-12);
  for (double d : {0.5, 1.0, 1.5}) {
    EXPECT_GT(kernel.Normalized(Vector2(0.0, d)), kernel.Normalized(Vector2(0.0, -d))) << d;
    // Symmetric across the alpha axis.
    EXPECT_NEAR(kernel.Normalized(Vector2(d, 0.5)), kernel.Normalized(Vector2(-d, 0.5)), 1e-12);
  }
  // Behind (against alpha) it falls off much faster than a normal would.
  EXPECT_LT(kernel.Normalized(Vector2(0.0, -1.0)), 0.5 * NormalizedGaussian(Vector2(0, 1.0), 1.0));
}

TEST(KernelsTest, ZeroSkewIsTheNormal) {
  const SkewNormalKernel kernel(0.8, 0.8, Vector2::Zero());
  for (double x : {-1.0, 0.0, 0.4, 1.3}) {
    EXPECT_NEAR(kernel.Normalized(Vector2(x, 0.2)), NormalizedGaussian(Vector2(x, 0.2), 0.8),
                1e-12);
  }
}

TEST(KernelsTest, SupportRadiusBoundsTheThresholdedSet) {
  const SkewNormalKernel kernel(0.45, 0.35, Vector2(2.0, -1.0));
  for (double p_th : {0.5, 0.6, 0.7}) {
    const double radius = kernel.SupportRadius(p_th);
    for (double angle = 0.0; angle < 6.28; angle += 0.05) {
      const Vector2 u = 1.001 * radius * Vector2(std::cos(angle), std::sin(angle));
      EXPECT_LE(kernel.Normalized(u), p_th) << p_th << " " << angle;
    }
  }
}

}  // namespace
}  // namespace fleetmap::extrapolation
