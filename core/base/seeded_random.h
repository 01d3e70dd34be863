// SeededRandom: the pseudo-random numbers of the evaluation protocol and of the distortions, the
// same with every standard library for a given seed (docs/design.md#seeds: seeds fixed and
// printed). The standard library's distributions are implementation-defined, so only
// std::mt19937_64's raw output (fully specified by the standard) is used and the uniform and
// normal variates are derived from it here. (Normal() goes through log, sin and cos, whose last
// bit may differ between C libraries.)
//
// Not thread-safe: one generator per thread or per task.
#pragma once

#include <cstdint>
#include <random>

namespace orbit {

// Mixes several integers into one well-spread 64-bit seed (SplitMix64 finaliser applied in turn),
// so that e.g. (seed, object, n, trial) gives independent streams for independent tasks.
std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t value);

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1), 53 random bits.
  double Uniform();

  // Uniform integer in [0, bound). REQUIRES: bound >= 1.
  std::uint64_t UniformInt(std::uint64_t bound);

  // Standard normal N(0, 1) by the Box-Muller transform (the second variate of each pair is kept
  // for the next call).
  double Normal();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

}  // namespace orbit
