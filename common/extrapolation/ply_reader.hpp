#pragma once

// A small, strict PLY reader for point clouds: `format ascii 1.0` or `binary_little_endian 1.0`,
// one `vertex` element with float/double (or float32/float64) x, y, z properties (other scalar
// vertex properties are skipped; other elements after the vertices are ignored). List properties
// on vertices, big-endian files, a truncated body, non-finite coordinates or more than
// `max_points` vertices are errors naming the file and the problem.
//
// Thread-safety: stateless.

#include <cstdint>
#include <string>

#include "common/core/status.hpp"
#include "common/extrapolation/point_cloud.hpp"

namespace fleetmap::extrapolation {

inline constexpr int64_t kDefaultMaxPlyPoints = 20'000'000;

// Errors: kNotFound (no file), kInvalidArgument (bad header or body), kResourceExhausted (too
// many vertices). An empty cloud (0 vertices) is not an error.
StatusOr<PointCloud> ReadPly(const std::string& path, int64_t max_points = kDefaultMaxPlyPoints);
// The same from bytes in memory; `source_name` names them in errors.
StatusOr<PointCloud> ParsePly(const std::string& bytes, const std::string& source_name,
                              int64_t max_points = kDefaultMaxPlyPoints);

// Writes `cloud` as binary little-endian PLY with float x y z (for tests and the simulator).
Status WritePly(const PointCloud& cloud, const std::string& path, bool ascii = false);

}  // namespace fleetmap::extrapolation
