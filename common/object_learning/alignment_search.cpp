#include "common/object_learning/alignment_search.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/object_learning/patch_transform.hpp"

namespace fleetmap::object_learning {

AlignmentResult AlignSnapshot(const Patch& snapshot, const float* target, const Alignment& start,
                              bool scan_rotations, double fine_factor, const EmOptions& options) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  AlignmentResult best{start, AlignedSquaredDistance(snapshot, start, target, kInf)};
  if (scan_rotations) {
    const int turns = std::max(
        1, static_cast<int>(std::lround(2.0 * std::numbers::pi / options.rotation_scan_step)));
    for (int i = 0; i < turns; ++i) {
      const double phi = start.dphi + i * (2.0 * std::numbers::pi / turns);
      for (const Alignment& candidate :
           {Alignment{start.dx, start.dy, phi}, Alignment{0, 0, phi}}) {
        const double d = AlignedSquaredDistance(snapshot, candidate, target, best.squared_distance);
        if (d < best.squared_distance) best = {candidate, d};
      }
    }
  }
  double shift = options.initial_shift_step * (scan_rotations ? 1.0 : fine_factor);
  double turn = options.initial_turn_step * (scan_rotations ? 1.0 : fine_factor);
  shift = std::max(shift, options.min_shift_step);
  while (shift >= options.min_shift_step) {
    const Alignment& a = best.alignment;
    const std::array<Alignment, 6> moves = {
        Alignment{a.dx + shift, a.dy, a.dphi}, Alignment{a.dx - shift, a.dy, a.dphi},
        Alignment{a.dx, a.dy + shift, a.dphi}, Alignment{a.dx, a.dy - shift, a.dphi},
        Alignment{a.dx, a.dy, a.dphi + turn},  Alignment{a.dx, a.dy, a.dphi - turn}};
    AlignmentResult step = best;
    for (const Alignment& move : moves) {
      const double d = AlignedSquaredDistance(snapshot, move, target, step.squared_distance);
      if (d < step.squared_distance) step = {move, d};
    }
    if (step.squared_distance < best.squared_distance) {
      best = step;
    } else {
      shift *= 0.5;
      turn *= 0.5;
    }
  }
  best.alignment.dphi = std::remainder(best.alignment.dphi, 2.0 * std::numbers::pi);
  return best;
}

}  // namespace fleetmap::object_learning
