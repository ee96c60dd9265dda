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

ShapeSize SizeOfContent(const float* values, int width, int height) {
  double m = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double v = std::max(0.0f, values[static_cast<size_t>(y) * width + x]);
      m += v;
      sx += v * x;
      sy += v * y;
      sxx += v * x * x;
      sxy += v * x * y;
      syy += v * y * y;
    }
  }
  ShapeSize size;
  size.mass = m;
  if (m <= 0.0) return size;
  const double cxx = sxx / m - (sx / m) * (sx / m);
  const double cxy = sxy / m - (sx / m) * (sy / m);
  const double cyy = syy / m - (sy / m) * (sy / m);
  const double mean = 0.5 * (cxx + cyy);
  const double spread = std::sqrt(std::max(0.0, 0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy));
  size.major = std::sqrt(std::max(0.0, mean + spread));
  size.minor = std::sqrt(std::max(0.0, mean - spread));
  return size;
}

bool MayMatch(const ShapeSize& a, const ShapeSize& b) {
  auto within = [](double p, double q, double factor) {
    return p <= factor * q && q <= factor * p;
  };
  return within(a.mass + 1.0, b.mass + 1.0, 2.5) && within(a.major + 1.0, b.major + 1.0, 2.0) &&
         within(a.minor + 1.0, b.minor + 1.0, 2.0);
}

AlignmentResult CentroidAlignment(const scene::Patch& snapshot, const float* target) {
  const PatchSampler sampler(snapshot);
  const Point2 shift = Centroid(target, snapshot) - Centroid(snapshot.occupancy.data(), snapshot);
  const Alignment a{shift.x(), shift.y(), 0.0};
  const CellBox target_box = NonZeroBox(target, snapshot.width, snapshot.height);
  return {a,
          sampler.SquaredDistance(a, target, target_box, std::numeric_limits<double>::infinity())};
}

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
