#include "common/vector_map/lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::vector_map {
namespace {

TEST(LatticeTest, SnapsToTheNearestLatticePointWithinTheBound) {
  const Lattice lattice(0.125, Point2(0.3, -0.7));
  for (double x = -2.0; x < 2.0; x += 0.0371) {
    const Point2 p(x, 0.77 * x + 0.01);
    const Point2 q = lattice.Snap(p);
    EXPECT_LE((q - p).norm(), lattice.MaxDisplacement() * (1 + 1e-12));
    const double kx = (q.x() - 0.3) / 0.125;
    const double ky = (q.y() + 0.7) / 0.125;
    EXPECT_NEAR(kx, std::round(kx), 1e-9);
    EXPECT_NEAR(ky, std::round(ky), 1e-9);
    EXPECT_EQ(lattice.Snap(q), q);
  }
}

TEST(LatticeTest, ZeroQuantumLeavesPointsAlone) {
  const Lattice lattice(0.0, Point2(1, 1));
  EXPECT_FALSE(lattice.enabled());
  EXPECT_EQ(lattice.Snap(Point2(0.123, 4.56)), Point2(0.123, 4.56));
  EXPECT_EQ(lattice.MaxDisplacement(), 0.0);
}

}  // namespace
}  // namespace fleetmap::vector_map
