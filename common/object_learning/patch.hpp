#pragma once

// The small occupancy grids object learning works on: snapshots, objects and templates, all of one
// common size, centred on the patch centre, and the rigid alignment that maps one onto another.

#include <vector>

#include "common/core/types.hpp"

namespace fleetmap::object_learning {

// A square or rectangular occupancy patch, row-major, values in [0, 1] (probability of
// occupancy). Cell (x, y) has its centre at ((x - (width - 1) / 2) * resolution,
// (y - (height - 1) / 2) * resolution) relative to the patch centre.
struct Patch {
  int width = 0;
  int height = 0;
  double resolution = 0.05;  // metres per cell
  std::vector<float> occupancy;
  // Which cells were observed (1) or not (0, e.g. the far side of an object the robot never saw);
  // unobserved cells are missing data, not empty space. Empty: every cell observed (objects,
  // templates).
  std::vector<float> weight;

  float at(int x, int y) const { return occupancy[static_cast<size_t>(y) * width + x]; }
  float& at(int x, int y) { return occupancy[static_cast<size_t>(y) * width + x]; }
  float WeightAt(int x, int y) const {
    return weight.empty() ? 1.0f : weight[static_cast<size_t>(y) * width + x];
  }
  bool empty() const { return occupancy.empty(); }
};

// A rigid transform of a patch about its centre: rotate by dphi, then shift by (dx, dy).
struct Alignment {
  double dx = 0.0;    // metres
  double dy = 0.0;    // metres
  double dphi = 0.0;  // radians, counter-clockwise
};

}  // namespace fleetmap::object_learning
