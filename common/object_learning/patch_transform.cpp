#include "common/object_learning/patch_transform.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace fleetmap::object_learning {
namespace {

// Walks the destination cells and hands each one's bilinear sample of the source to `visit`,
// which returns false to stop early.
template <typename Visit>
void ForEachSample(const Patch& source, const Alignment& alignment, Visit&& visit) {
  assert(!source.empty());
  const int w = source.width;
  const int h = source.height;
  const double cx = 0.5 * (w - 1);
  const double cy = 0.5 * (h - 1);
  const double c = std::cos(alignment.dphi);
  const double s = std::sin(alignment.dphi);
  // Source cell coordinates of destination cell (x, y): R(-phi) ((x, y) - centre - d) + centre.
  const double shift_x = alignment.dx / source.resolution;
  const double shift_y = alignment.dy / source.resolution;
  const float* data = source.occupancy.data();
  for (int y = 0; y < h; ++y) {
    const double py = y - cy - shift_y;
    for (int x = 0; x < w; ++x) {
      const double px = x - cx - shift_x;
      const double u = c * px + s * py + cx;
      const double v = -s * px + c * py + cy;
      float value = 0.0f;
      if (u > -1.0 && v > -1.0 && u < w && v < h) {
        const int u0 = static_cast<int>(std::floor(u));
        const int v0 = static_cast<int>(std::floor(v));
        const float fu = static_cast<float>(u - u0);
        const float fv = static_cast<float>(v - v0);
        auto at = [&](int xx, int yy) -> float {
          return (xx >= 0 && yy >= 0 && xx < w && yy < h) ? data[static_cast<size_t>(yy) * w + xx]
                                                          : 0.0f;
        };
        value = (1.0f - fv) * ((1.0f - fu) * at(u0, v0) + fu * at(u0 + 1, v0)) +
                fv * ((1.0f - fu) * at(u0, v0 + 1) + fu * at(u0 + 1, v0 + 1));
      }
      if (!visit(static_cast<size_t>(y) * w + x, value)) return;
    }
  }
}

}  // namespace

Patch ZeroPatch(int width, int height, double resolution) {
  Patch patch;
  patch.width = width;
  patch.height = height;
  patch.resolution = resolution;
  patch.occupancy.assign(static_cast<size_t>(width) * height, 0.0f);
  return patch;
}

void TransformPatchInto(const Patch& source, const Alignment& alignment, float* out) {
  ForEachSample(source, alignment, [out](size_t i, float value) {
    out[i] = value;
    return true;
  });
}

void TransformPatch(const Patch& source, const Alignment& alignment, Patch* out) {
  *out = ZeroPatch(source.width, source.height, source.resolution);
  TransformPatchInto(source, alignment, out->occupancy.data());
}

double AlignedSquaredDistance(const Patch& source, const Alignment& alignment, const float* target,
                              double bound) {
  double sum = 0.0;
  // Checking the bound once per cell costs more than it saves; once per 64 cells is enough.
  size_t count = 0;
  ForEachSample(source, alignment, [&](size_t i, float value) {
    const double d = static_cast<double>(value) - target[i];
    sum += d * d;
    return (++count & 63u) != 0 || sum < bound;
  });
  return sum;
}

}  // namespace fleetmap::object_learning
