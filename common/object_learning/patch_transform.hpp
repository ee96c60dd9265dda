#pragma once

// f(mu, delta) of ALGORITHMS.md 2: a patch resampled under a rigid alignment (rotation by dphi
// about the patch centre, then a shift by (dx, dy)), by bilinear interpolation; outside the source
// patch reads as 0 (no object). Also the squared distance the EM minimises.
//
// Thread-safety: stateless.

#include <Eigen/Core>

#include "common/object_learning/patch.hpp"

namespace fleetmap::object_learning {

// out[x] = source(R(-dphi) (x - d)): the source content moved by `alignment`. `out` gets the
// source's size and resolution. Requires a non-empty source.
void TransformPatch(const Patch& source, const Alignment& alignment, Patch* out);

// The same, written into a row vector of width * height values (row-major), for the EM's
// matrices. `out` must have that size.
void TransformPatchInto(const Patch& source, const Alignment& alignment, float* out);

// Sum over cells of (f(source, alignment)[x] - target[x])^2; target is row-major with the
// source's size. Stops early (returning a value >= bound) once the partial sum exceeds `bound`.
double AlignedSquaredDistance(const Patch& source, const Alignment& alignment, const float* target,
                              double bound);

// A patch of the given size filled with zeros.
Patch ZeroPatch(int width, int height, double resolution);

}  // namespace fleetmap::object_learning
