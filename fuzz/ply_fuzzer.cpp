// Fuzz target: a PLY point cloud (`fleetmap extrapolate --cloud`): header and ASCII or binary
// little-endian body. The limit is small so that a header claiming many points costs the fuzzer
// little; every point the reader returns is finite.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/core/check.hpp"
#include "common/extrapolation/ply_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  constexpr int64_t kMaxPoints = 100'000;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const StatusOr<extrapolation::PointCloud> cloud =
      extrapolation::ParsePly(bytes, "fuzz.ply", kMaxPoints);
  if (!cloud.ok()) return 0;
  FLEETMAP_CHECK(static_cast<int64_t>(cloud->size()) <= kMaxPoints);
  for (const extrapolation::Point3& point : *cloud) FLEETMAP_CHECK(point.allFinite());
  return 0;
}
