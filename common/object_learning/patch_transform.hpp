#pragma once

// f(mu, delta) of ALGORITHMS.md 2: a patch resampled under a rigid alignment (rotation by dphi
// about the patch centre, then a shift by (dx, dy)), by bilinear interpolation; outside the source
// patch reads as 0 (no object). Also the squared distance the EM minimises.
//
// Thread-safety: stateless.

#include <Eigen/Core>
#include <vector>

#include "common/object_learning/alignment.hpp"

namespace fleetmap::object_learning {

// out[x] = source(R(-dphi) (x - d)): the source content moved by `alignment`. `out` gets the
// source's size and resolution. The weights (observed cells) move with it: outside the source, a
// patch with weights reads as unobserved (weight 0), one without as observed and empty.
// Requires a non-empty source.
void TransformPatch(const scene::Patch& source, const Alignment& alignment, scene::Patch* out);

// The same, written into row vectors of width * height values (row-major), for the EM's
// matrices. `out_weight` may be null.
void TransformPatchInto(const scene::Patch& source, const Alignment& alignment, float* out,
                        float* out_weight);

// Sum over cells of w[x] (f(source, alignment)[x] - target[x])^2, w the moved weights; target is
// row-major with the source's size. Stops early (returning a value >= bound) once the partial
// sum exceeds `bound`.
double AlignedSquaredDistance(const scene::Patch& source, const Alignment& alignment,
                              const float* target, double bound);

// `inner` then `outer`: f(f(p, inner), outer) = f(p, Compose(outer, inner)) (up to resampling).
Alignment Compose(const Alignment& outer, const Alignment& inner);
// The alignment that undoes `a`.
Alignment Inverse(const Alignment& a);

// An inclusive rectangle of patch cells (empty when x1 < x0 or y1 < y0).
struct CellBox {
  int x0 = 0;
  int y0 = 0;
  int x1 = -1;
  int y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
};

// Occupancy below this counts as empty when bounding the cells a distance visits: learned objects
// are averages, faintly non-zero everywhere, and the cells they leave out change a distance by at
// most their count times 1e-4.
inline constexpr float kNegligibleOccupancy = 0.01f;

// The smallest box holding every value of a row-major width x height grid that is not
// negligible (|v| >= kNegligibleOccupancy).
CellBox NonZeroBox(const float* values, int width, int height);

// AlignedSquaredDistance with the non-zero boxes of the source's occupancy and of the target
// given (a caller that scores many alignments computes them once); only their union (the
// source's moved) is visited, since cells where both are 0 add nothing.
double AlignedSquaredDistance(const scene::Patch& source, const CellBox& source_box,
                              const Alignment& alignment, const float* target,
                              const CellBox& target_box, double bound);

// Scores many alignments of one source patch quickly: keeps a copy of the source padded with a
// border of one cell (so bilinear samples need no bounds checks) and walks the destination cells
// incrementally. Same results as AlignedSquaredDistance up to float rounding.
class PatchSampler {
 public:
  explicit PatchSampler(const scene::Patch& source);
  const CellBox& box() const { return box_; }  // the source's non-negligible cells
  double SquaredDistance(const Alignment& alignment, const float* target, const CellBox& target_box,
                         double bound) const;
  // f(source, alignment) and its weights over the whole patch (row-major), as TransformPatchInto.
  void Sample(const Alignment& alignment, float* out, float* out_weight) const;

 private:
  // The bilinear value and weight at source cell coordinates (u, v); outside the patch, 0 and
  // the weight of an unobserved (or, without weights, observed) cell.
  void Bilinear(float u, float v, float* value, float* weight) const;

  int width_;
  int height_;
  double resolution_;
  bool has_weight_;
  CellBox box_;
  std::vector<float> value_;   // (width + 2) x (height + 2)
  std::vector<float> weight_;  // same; outside the source: 0 with weights, 1 without
};

// A patch of the given size filled with zeros.
scene::Patch ZeroPatch(int width, int height, double resolution);

}  // namespace fleetmap::object_learning
