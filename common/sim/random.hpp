#pragma once

// The simulator's only source of randomness. std::mt19937 is fully specified by the C++ standard,
// but std::uniform_*_distribution and std::normal_distribution are not: their outputs differ
// between standard libraries. Every distribution here is written out explicitly on top of the raw
// 32-bit engine output, so a seed gives the same numbers with any standard library. The normal
// deviate uses std::log / std::sqrt / std::cos (Box-Muller); those are correctly rounded in glibc
// on x86-64, so results are bit-identical on this platform, and agree to the last ulp elsewhere.
//
// Thread-safety: not thread-safe; one Random per thread (or per simulated component).

#include <cstdint>
#include <random>

namespace fleetmap::sim {

class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}

  // A raw 32-bit word of the engine.
  uint32_t Next() { return static_cast<uint32_t>(engine_()); }
  // Uniform in [0, 1), 53 random bits from two engine words.
  double Uniform();
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [lo, hi] (inclusive), unbiased (rejection sampling). Requires lo <= hi.
  int UniformInt(int lo, int hi);
  // True with probability p.
  bool Bernoulli(double p) { return Uniform() < p; }
  // Gaussian with the given mean and standard deviation (Box-Muller, both deviates used).
  double Gaussian(double mean, double stddev);

  // A seed for a sub-component derived from this stream, so components draw independently.
  uint32_t Fork() { return Next(); }

 private:
  std::mt19937 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace fleetmap::sim
