#include "common/object_learning/alignment_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/object_learning/patch_transform.hpp"
#include "tests/unit/object_learning/test_patches.hpp"

namespace fleetmap::object_learning {
namespace {

using testing::ShapePatch;
using testing::TestShape;

TEST(AlignmentSearchTest, RecoversAKnownRotationAndShift) {
  const scene::Patch l = ShapePatch(TestShape::kL, 31);
  for (const Alignment truth : {Alignment{0.10, -0.05, 2.0}, Alignment{-0.07, 0.12, -0.6},
                                Alignment{0.0, 0.0, std::numbers::pi}}) {
    scene::Patch target;
    TransformPatch(l, truth, &target);
    const AlignmentResult r =
        AlignSnapshot(l, target.occupancy.data(), Alignment{}, true, 1.0, EmOptions{});
    EXPECT_NEAR(r.alignment.dx, truth.dx, 0.02);
    EXPECT_NEAR(r.alignment.dy, truth.dy, 0.02);
    EXPECT_NEAR(std::remainder(r.alignment.dphi - truth.dphi, 2.0 * std::numbers::pi), 0.0, 0.04);
    EXPECT_LT(r.squared_distance, 0.5);
  }
}

TEST(AlignmentSearchTest, ClimbWithoutScanStaysLocal) {
  const scene::Patch bar = ShapePatch(TestShape::kBar, 31);
  scene::Patch target;
  const Alignment truth{0.03, 0.02, 0.1};
  TransformPatch(bar, truth, &target);
  const AlignmentResult r =
      AlignSnapshot(bar, target.occupancy.data(), Alignment{}, false, 1.0, EmOptions{});
  EXPECT_NEAR(r.alignment.dx, truth.dx, 0.015);
  EXPECT_NEAR(r.alignment.dy, truth.dy, 0.015);
  EXPECT_NEAR(r.alignment.dphi, truth.dphi, 0.03);
}

TEST(AlignmentSearchTest, NeverWorseThanTheStart) {
  const scene::Patch l = ShapePatch(TestShape::kL);
  const scene::Patch ring = ShapePatch(TestShape::kRing);
  const Alignment start{0.05, 0.0, 0.7};
  const double at_start = AlignedSquaredDistance(l, start, ring.occupancy.data(), 1e300);
  const AlignmentResult r = AlignSnapshot(l, ring.occupancy.data(), start, false, 1.0, EmOptions{});
  EXPECT_LE(r.squared_distance, at_start + 1e-9);
}

}  // namespace
}  // namespace fleetmap::object_learning
