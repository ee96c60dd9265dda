#pragma once

// Small synthetic patches for the object-learning tests: an L, a ring and a bar on a 5 cm grid.

#include <cmath>
#include <numbers>

#include "common/object_learning/alignment.hpp"
#include "common/object_learning/patch_transform.hpp"

namespace fleetmap::object_learning::testing {

enum class TestShape { kL, kRing, kBar };

// A `side` x `side` patch with the shape's outline (one cell thick, value 1) centred.
inline scene::Patch ShapePatch(TestShape shape, int side = 25) {
  scene::Patch p = ZeroPatch(side, side, 0.05);
  const int c = side / 2;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const int dx = x - c, dy = y - c;
      bool on = false;
      switch (shape) {
        case TestShape::kL:  // two arms of 11 cells, 3 thick, corner at (-5, -5)
          on = (dy >= -5 && dy <= -3 && dx >= -5 && dx <= 5) ||
               (dx >= -5 && dx <= -3 && dy >= -5 && dy <= 5);
          break;
        case TestShape::kRing: {
          const double r = std::hypot(dx, dy);
          on = r >= 3.5 && r <= 4.6;
          break;
        }
        case TestShape::kBar:  // 14 x 4 cells, outline
          on = (std::abs(dx) <= 7 && std::abs(dy) <= 2) && (std::abs(dx) == 7 || std::abs(dy) == 2);
          break;
      }
      if (on) p.at(x, y) = 1.0f;
    }
  }
  return p;
}

}  // namespace fleetmap::object_learning::testing
