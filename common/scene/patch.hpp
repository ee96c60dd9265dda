#pragma once

// A small occupancy grid centred on its own centre: what object learning works on (snapshots,
// objects, templates) and what the object-model topics carry.

#include <cstddef>
#include <vector>

namespace fleetmap::scene {

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

}  // namespace fleetmap::scene
