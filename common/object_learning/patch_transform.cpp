#include "common/object_learning/patch_transform.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/core/check.hpp"

namespace fleetmap::object_learning {
namespace {

CellBox WholePatch(const scene::Patch& patch) { return {0, 0, patch.width - 1, patch.height - 1}; }

// Walks the destination cells and hands each one's bilinear samples of the source (value and
// weight) to `visit`, which returns false to stop early.
template <typename Visit>
void ForEachSample(const scene::Patch& source, const Alignment& alignment, const CellBox& box,
                   Visit&& visit) {
  FLEETMAP_CHECK(!source.empty());
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
  const float* weights = source.weight.empty() ? nullptr : source.weight.data();
  const float outside_weight = weights ? 0.0f : 1.0f;
  for (int y = box.y0; y <= box.y1; ++y) {
    const double py = y - cy - shift_y;
    for (int x = box.x0; x <= box.x1; ++x) {
      const double px = x - cx - shift_x;
      const double u = c * px + s * py + cx;
      const double v = -s * px + c * py + cy;
      float value = 0.0f;
      float weight = outside_weight;
      if (u > -1.0 && v > -1.0 && u < w && v < h) {
        const int u0 = static_cast<int>(std::floor(u));
        const int v0 = static_cast<int>(std::floor(v));
        const float fu = static_cast<float>(u - u0);
        const float fv = static_cast<float>(v - v0);
        auto at = [&](const float* grid, float outside, int xx, int yy) -> float {
          return (xx >= 0 && yy >= 0 && xx < w && yy < h) ? grid[static_cast<size_t>(yy) * w + xx]
                                                          : outside;
        };
        auto sample = [&](const float* grid, float outside) {
          return (1.0f - fv) * ((1.0f - fu) * at(grid, outside, u0, v0) +
                                fu * at(grid, outside, u0 + 1, v0)) +
                 fv * ((1.0f - fu) * at(grid, outside, u0, v0 + 1) +
                       fu * at(grid, outside, u0 + 1, v0 + 1));
        };
        value = sample(data, 0.0f);
        if (weights) weight = sample(weights, 0.0f);
      }
      if (!visit(static_cast<size_t>(y) * w + x, value, weight)) return;
    }
  }
}

}  // namespace

Alignment Compose(const Alignment& outer, const Alignment& inner) {
  const double c = std::cos(outer.dphi), s = std::sin(outer.dphi);
  return {c * inner.dx - s * inner.dy + outer.dx, s * inner.dx + c * inner.dy + outer.dy,
          outer.dphi + inner.dphi};
}

Alignment Inverse(const Alignment& a) {
  const double c = std::cos(a.dphi), s = std::sin(a.dphi);
  return {-(c * a.dx + s * a.dy), -(-s * a.dx + c * a.dy), -a.dphi};
}

scene::Patch ZeroPatch(int width, int height, double resolution) {
  scene::Patch patch;
  patch.width = width;
  patch.height = height;
  patch.resolution = resolution;
  patch.occupancy.assign(static_cast<size_t>(width) * height, 0.0f);
  return patch;
}

void TransformPatchInto(const scene::Patch& source, const Alignment& alignment, float* out,
                        float* out_weight) {
  ForEachSample(source, alignment, WholePatch(source),
                [out, out_weight](size_t i, float value, float weight) {
                  out[i] = value;
                  if (out_weight) out_weight[i] = weight;
                  return true;
                });
}

void TransformPatch(const scene::Patch& source, const Alignment& alignment, scene::Patch* out) {
  *out = ZeroPatch(source.width, source.height, source.resolution);
  if (!source.weight.empty()) out->weight.assign(out->occupancy.size(), 0.0f);
  TransformPatchInto(source, alignment, out->occupancy.data(),
                     source.weight.empty() ? nullptr : out->weight.data());
}

namespace {

// The cells a distance between a moved source and a target visits: the union of the target's
// non-zero box and the moved source's (its corners moved, plus a cell for the bilinear spread),
// clipped to the patch.
CellBox VisitedBox(const CellBox& target_box, const CellBox& source_box, int width, int height,
                   double resolution, const Alignment& alignment) {
  CellBox box = target_box;
  if (!source_box.empty()) {
    const double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
    const double c = std::cos(alignment.dphi), s = std::sin(alignment.dphi);
    const double sx = alignment.dx / resolution, sy = alignment.dy / resolution;
    for (const double x : {source_box.x0 - 1.0, source_box.x1 + 1.0}) {
      for (const double y : {source_box.y0 - 1.0, source_box.y1 + 1.0}) {
        const double u = c * (x - cx) - s * (y - cy) + cx + sx;
        const double v = s * (x - cx) + c * (y - cy) + cy + sy;
        box.x0 = std::min(box.x0, static_cast<int>(std::floor(u)));
        box.y0 = std::min(box.y0, static_cast<int>(std::floor(v)));
        box.x1 = std::max(box.x1, static_cast<int>(std::ceil(u)));
        box.y1 = std::max(box.y1, static_cast<int>(std::ceil(v)));
      }
    }
  }
  box.x0 = std::max(box.x0, 0);
  box.y0 = std::max(box.y0, 0);
  box.x1 = std::min(box.x1, width - 1);
  box.y1 = std::min(box.y1, height - 1);
  return box;
}

}  // namespace

CellBox NonZeroBox(const float* values, int width, int height) {
  CellBox box{width, height, -1, -1};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (std::abs(values[static_cast<size_t>(y) * width + x]) < kNegligibleOccupancy) continue;
      box.x0 = std::min(box.x0, x);
      box.y0 = std::min(box.y0, y);
      box.x1 = std::max(box.x1, x);
      box.y1 = std::max(box.y1, y);
    }
  }
  return box;
}

double AlignedSquaredDistance(const scene::Patch& source, const Alignment& alignment,
                              const float* target, double bound) {
  return AlignedSquaredDistance(
      source, NonZeroBox(source.occupancy.data(), source.width, source.height), alignment, target,
      NonZeroBox(target, source.width, source.height), bound);
}

double AlignedSquaredDistance(const scene::Patch& source, const CellBox& source_box,
                              const Alignment& alignment, const float* target,
                              const CellBox& target_box, double bound) {
  // Cells where both the moved source and the target are 0 add nothing: visit only the union of
  // the target's non-zero box and the moved source's (its corners moved, plus a cell for the
  // bilinear spread).
  const CellBox box =
      VisitedBox(target_box, source_box, source.width, source.height, source.resolution, alignment);
  if (box.empty()) return 0.0;
  double sum = 0.0;
  // Checking the bound once per cell costs more than it saves; once per 64 cells is enough.
  size_t count = 0;
  ForEachSample(source, alignment, box, [&](size_t i, float value, float weight) {
    const double d = static_cast<double>(value) - target[i];
    sum += weight * d * d;
    return (++count & 63u) != 0 || sum < bound;
  });
  return sum;
}

PatchSampler::PatchSampler(const scene::Patch& source)
    : width_(source.width),
      height_(source.height),
      resolution_(source.resolution),
      has_weight_(!source.weight.empty()),
      box_(NonZeroBox(source.occupancy.data(), source.width, source.height)) {
  const int pw = width_ + 2;
  value_.assign(static_cast<size_t>(pw) * (height_ + 2), 0.0f);
  weight_.assign(value_.size(), has_weight_ ? 0.0f : 1.0f);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const size_t i = static_cast<size_t>(y + 1) * pw + (x + 1);
      value_[i] = source.at(x, y);
      weight_[i] = source.WeightAt(x, y);
    }
  }
}

inline void PatchSampler::Bilinear(float u, float v, float* value, float* weight) const {
  if (!(u > -1.0f && v > -1.0f && u < width_ && v < height_)) {
    *value = 0.0f;
    *weight = has_weight_ ? 0.0f : 1.0f;
    return;
  }
  // u + 1 > 0: truncation is floor. Padded index of cell (iu, iv) is (iu + 1, iv + 1).
  const int pw = width_ + 2;
  const int iu = static_cast<int>(u + 1.0f);
  const int iv = static_cast<int>(v + 1.0f);
  const float fu = u + 1.0f - iu, fv = v + 1.0f - iv;
  const size_t i = static_cast<size_t>(iv) * pw + iu;
  const float w00 = (1.0f - fu) * (1.0f - fv), w10 = fu * (1.0f - fv);
  const float w01 = (1.0f - fu) * fv, w11 = fu * fv;
  *value = w00 * value_[i] + w10 * value_[i + 1] + w01 * value_[i + pw] + w11 * value_[i + pw + 1];
  *weight =
      w00 * weight_[i] + w10 * weight_[i + 1] + w01 * weight_[i + pw] + w11 * weight_[i + pw + 1];
}

double PatchSampler::SquaredDistance(const Alignment& alignment, const float* target,
                                     const CellBox& target_box, double bound) const {
  // The union of the target's box and the moved source box (see AlignedSquaredDistance).
  const CellBox box = VisitedBox(target_box, box_, width_, height_, resolution_, alignment);
  if (box.empty()) return 0.0;
  const double cx = 0.5 * (width_ - 1), cy = 0.5 * (height_ - 1);
  const double c = std::cos(alignment.dphi), s = std::sin(alignment.dphi);
  const double sx = alignment.dx / resolution_, sy = alignment.dy / resolution_;
  double sum = 0.0;
  for (int y = box.y0; y <= box.y1; ++y) {
    // Source coordinates of destination (x, y): R(-phi) ((x, y) - centre - d) + centre.
    const double px = box.x0 - cx - sx, py = y - cy - sy;
    float u = static_cast<float>(c * px + s * py + cx);
    float v = static_cast<float>(-s * px + c * py + cy);
    const float du = static_cast<float>(c), dv = static_cast<float>(-s);
    const float* t = target + static_cast<size_t>(y) * width_;
    float row = 0.0f;
    for (int x = box.x0; x <= box.x1; ++x, u += du, v += dv) {
      float f, w;
      Bilinear(u, v, &f, &w);
      const float d = f - t[x];
      row += w * d * d;
    }
    sum += row;
    if (sum >= bound) return sum;
  }
  return sum;
}

void PatchSampler::Sample(const Alignment& alignment, float* out, float* out_weight) const {
  const double cx = 0.5 * (width_ - 1), cy = 0.5 * (height_ - 1);
  const double c = std::cos(alignment.dphi), s = std::sin(alignment.dphi);
  const double sx = alignment.dx / resolution_, sy = alignment.dy / resolution_;
  for (int y = 0; y < height_; ++y) {
    const double px = -cx - sx, py = y - cy - sy;
    float u = static_cast<float>(c * px + s * py + cx);
    float v = static_cast<float>(-s * px + c * py + cy);
    const float du = static_cast<float>(c), dv = static_cast<float>(-s);
    for (int x = 0; x < width_; ++x, u += du, v += dv) {
      float f, w;
      Bilinear(u, v, &f, &w);
      const size_t o = static_cast<size_t>(y) * width_ + x;
      out[o] = f;
      if (out_weight) out_weight[o] = w;
    }
  }
}

}  // namespace fleetmap::object_learning
