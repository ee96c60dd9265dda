#include "common/object_learning/patch_transform.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "tests/unit/object_learning/test_patches.hpp"

namespace fleetmap::object_learning {
namespace {

using testing::ShapePatch;
using testing::TestShape;

TEST(PatchTransformTest, IdentityKeepsThePatch) {
  const scene::Patch p = ShapePatch(TestShape::kL);
  scene::Patch out;
  TransformPatch(p, Alignment{}, &out);
  EXPECT_EQ(out.occupancy, p.occupancy);
}

TEST(PatchTransformTest, QuarterTurnPermutesCells) {
  const scene::Patch p = ShapePatch(TestShape::kL);
  scene::Patch out;
  TransformPatch(p, Alignment{0.0, 0.0, std::numbers::pi / 2.0}, &out);
  const int c = p.width / 2;
  // Counter-clockwise by 90 degrees: the content at (x, y) moves to (c - (y - c), c + (x - c)).
  for (int y = 0; y < p.height; ++y) {
    for (int x = 0; x < p.width; ++x) {
      EXPECT_NEAR(out.at(c - (y - c), c + (x - c)), p.at(x, y), 1e-5) << x << ", " << y;
    }
  }
}

TEST(PatchTransformTest, ShiftMovesByWholeCells) {
  const scene::Patch p = ShapePatch(TestShape::kBar);
  scene::Patch out;
  TransformPatch(p, Alignment{0.10, -0.05, 0.0}, &out);  // +2 cells in x, -1 in y
  for (int y = 1; y < p.height; ++y) {
    for (int x = 0; x + 2 < p.width; ++x) {
      EXPECT_NEAR(out.at(x + 2, y - 1), p.at(x, y), 1e-5);
    }
  }
}

TEST(PatchTransformTest, ComposeAndInverse) {
  const scene::Patch p = ShapePatch(TestShape::kL);
  const Alignment a{0.05, 0.1, 0.3}, b{-0.1, 0.02, -1.1};
  scene::Patch ab, a_then_b, tmp, back;
  TransformPatch(p, a, &tmp);
  TransformPatch(tmp, b, &a_then_b);
  TransformPatch(p, Compose(b, a), &ab);
  double diff = 0.0;
  for (size_t i = 0; i < ab.occupancy.size(); ++i)
    diff += std::abs(ab.occupancy[i] - a_then_b.occupancy[i]);
  EXPECT_LT(diff / ab.occupancy.size(), 0.02);  // two resamplings blur a little
  const Alignment id = Compose(Inverse(a), a);
  EXPECT_NEAR(id.dx, 0.0, 1e-12);
  EXPECT_NEAR(id.dy, 0.0, 1e-12);
  EXPECT_NEAR(id.dphi, 0.0, 1e-12);
}

TEST(PatchTransformTest, SamplerMatchesReferenceDistance) {
  scene::Patch p = ShapePatch(TestShape::kL);
  p.weight.assign(p.occupancy.size(), 1.0f);
  for (int x = 0; x < p.width; ++x) p.weight[x] = 0.0f;  // an unobserved row
  const scene::Patch target = ShapePatch(TestShape::kRing);
  const PatchSampler sampler(p);
  const CellBox box = NonZeroBox(target.occupancy.data(), target.width, target.height);
  for (const Alignment& a : {Alignment{}, Alignment{0.07, -0.03, 0.4}, Alignment{-0.2, 0.1, 2.5}}) {
    const double reference = AlignedSquaredDistance(p, a, target.occupancy.data(),
                                                    std::numeric_limits<double>::infinity());
    EXPECT_NEAR(sampler.SquaredDistance(a, target.occupancy.data(), box,
                                        std::numeric_limits<double>::infinity()),
                reference, 1e-3 * (1.0 + reference));
  }
}

TEST(PatchTransformTest, UnobservedCellsDoNotCount) {
  scene::Patch p = ShapePatch(TestShape::kBar);
  const scene::Patch target = ShapePatch(TestShape::kRing);
  const double inf = std::numeric_limits<double>::infinity();
  const double all = AlignedSquaredDistance(p, Alignment{}, target.occupancy.data(), inf);
  p.weight.assign(p.occupancy.size(), 0.0f);
  EXPECT_GT(all, 10.0);
  EXPECT_EQ(AlignedSquaredDistance(p, Alignment{}, target.occupancy.data(), inf), 0.0);
}

}  // namespace
}  // namespace fleetmap::object_learning
