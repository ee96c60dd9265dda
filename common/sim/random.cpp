#include "common/sim/random.hpp"

#include <cmath>
#include <numbers>

#include "common/core/check.hpp"

namespace fleetmap::sim {

double Random::Uniform() {
  const uint64_t high = Next() >> 5;                                            // 27 bits
  const uint64_t low = Next() >> 6;                                             // 26 bits
  return static_cast<double>((high << 26) | low) * (1.0 / 9007199254740992.0);  // 2^-53
}

int Random::UniformInt(int lo, int hi) {
  FLEETMAP_CHECK(lo <= hi);
  const uint64_t span = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1;
  if (span > 0xFFFFFFFFull) return static_cast<int>(lo + static_cast<int64_t>(Next()));
  // Reject the top partial bucket so every value is equally likely.
  const uint64_t limit = (uint64_t{1} << 32) - ((uint64_t{1} << 32) % span);
  uint64_t word = Next();
  while (word >= limit) word = Next();
  return static_cast<int>(lo + static_cast<int64_t>(word % span));
}

double Random::Gaussian(double mean, double stddev) {
  if (has_spare_) {
    has_spare_ = false;
    return mean + stddev * spare_;
  }
  double u1 = Uniform();
  while (u1 <= 0.0) u1 = Uniform();
  const double u2 = Uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * std::numbers::pi * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return mean + stddev * radius * std::cos(angle);
}

}  // namespace fleetmap::sim
