#include "common/object_learning/memory_plan.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fleetmap::object_learning {
namespace {

// [1 2 1] / 4 around old cell (cx, cy), separably, outside the patch reading as 0.
float Smoothed(const std::vector<float>& values, int side, int cx, int cy) {
  constexpr float kKernel[3] = {0.25f, 0.5f, 0.25f};
  float sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = cx + dx, y = cy + dy;
      if (x < 0 || y < 0 || x >= side || y >= side) continue;
      sum += kKernel[dx + 1] * kKernel[dy + 1] * values[static_cast<size_t>(y) * side + x];
    }
  }
  return sum;
}

}  // namespace

double ExtractionBytes(int maps, int64_t map_cells) {
  // Per map: occupied and clear masks (2 bytes a cell); while one map is differenced: free,
  // not-free and dilation masks, the difference mask and its filtered copy, and the low-pass
  // summed-area table (4 bytes), about 24 bytes a cell with the regions' cell lists.
  return static_cast<double>(map_cells) * (2.0 * maps + 24.0);
}

double LearningBytes(int snapshots, int64_t patch_cells, int max_objects, int per_map,
                     int exact_snapshots) {
  const double s = snapshots, c = static_cast<double>(patch_cells), n = max_objects;
  // Snapshot patches (values and weights, floats) held by the extracted set and the EM problem.
  const double patches = 2.0 * 8.0 * s * c;
  // Objects and templates (doubles) with the copies one EM iteration keeps (previous objects,
  // M-step right-hand sides and solution, streamed sums, the best run's model): about 16 N x C.
  const double model = 16.0 * 8.0 * n * c;
  // Pair alignments, correspondences and log-likelihoods (snapshots x objects), twice.
  const double pairs = 2.0 * (24.0 + 3.0 * 8.0) * s * n + 32.0 * n * n;
  // The exact E-step: forward and backward tables of 2^K doubles per object.
  const int k = std::min(per_map, exact_snapshots);
  const double e_step = k <= 0 ? 0.0 : 2.0 * 8.0 * (n + 1.0) * std::ldexp(1.0, k);
  return patches + model + pairs + e_step;
}

void CoarsenSnapshots(SnapshotSet* set) {
  for (Snapshot& snapshot : set->snapshots) {
    scene::Patch& patch = snapshot.patch;
    const int side = patch.width;
    const int half = side / 2;
    const int new_half = (half + 1) / 2;
    const int new_side = 2 * new_half + 1;
    scene::Patch out;
    out.width = out.height = new_side;
    out.resolution = 2.0 * patch.resolution;
    out.occupancy.assign(static_cast<size_t>(new_side) * new_side, 0.0f);
    if (!patch.weight.empty()) out.weight.assign(out.occupancy.size(), 0.0f);
    for (int y = 0; y < new_side; ++y) {
      for (int x = 0; x < new_side; ++x) {
        const int cx = half + 2 * (x - new_half), cy = half + 2 * (y - new_half);
        const size_t i = static_cast<size_t>(y) * new_side + x;
        out.occupancy[i] = Smoothed(patch.occupancy, side, cx, cy);
        if (!patch.weight.empty()) out.weight[i] = Smoothed(patch.weight, side, cx, cy);
      }
    }
    patch = std::move(out);
  }
}

}  // namespace fleetmap::object_learning
