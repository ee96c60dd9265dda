#include "common/object_learning/alignment_search.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/object_learning/patch_transform.hpp"

namespace fleetmap::object_learning {
namespace {

// Occupancy-weighted centroid of a row-major grid of the patch's size, metres from its centre.
Point2 Centroid(const float* values, const scene::Patch& shape) {
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (int y = 0; y < shape.height; ++y) {
    for (int x = 0; x < shape.width; ++x) {
      const double v = std::max(0.0f, values[static_cast<size_t>(y) * shape.width + x]);
      sum += v;
      sx += v * x;
      sy += v * y;
    }
  }
  if (sum <= 0.0) return Point2::Zero();
  return Point2(sx / sum - 0.5 * (shape.width - 1), sy / sum - 0.5 * (shape.height - 1)) *
         shape.resolution;
}

}  // namespace

AlignmentResult AlignSnapshot(const scene::Patch& snapshot, const float* target,
                              const Alignment& start, bool scan_rotations, double fine_factor,
                              const EmOptions& options) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const PatchSampler sampler(snapshot);
  const CellBox target_box = NonZeroBox(target, snapshot.width, snapshot.height);
  auto distance = [&](const Alignment& a, double bound) {
    return sampler.SquaredDistance(a, target, target_box, bound);
  };
  AlignmentResult best{start, distance(start, kInf)};
  if (scan_rotations) {
    // Each rotation is tried at the start's shift and at the shift that puts the moved source's
    // centroid on the target's (metres from the patch centre).
    const Point2 source_centroid = Centroid(snapshot.occupancy.data(), snapshot);
    const Point2 target_centroid = Centroid(target, snapshot);
    const int turns = std::max(
        1, static_cast<int>(std::lround(2.0 * std::numbers::pi / options.rotation_scan_step)));
    for (int i = 0; i < turns; ++i) {
      const double phi = start.dphi + i * (2.0 * std::numbers::pi / turns);
      const Point2 shift = target_centroid - Eigen::Rotation2Dd(phi) * source_centroid;
      for (const Alignment& candidate :
           {Alignment{start.dx, start.dy, phi}, Alignment{shift.x(), shift.y(), phi}}) {
        const double d = distance(candidate, best.squared_distance);
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
      const double d = distance(move, step.squared_distance);
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
