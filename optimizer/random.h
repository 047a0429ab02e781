// Small, portable random numbers for the optimizer: seeds, Latin hypercube jitter and shuffles.
// Written out here (rather than std::uniform_real_distribution) because the standard leaves
// the distributions' algorithms to the library, and campaigns must reproduce bit for bit on
// every platform and after a resume.
#pragma once

#include <cstdint>

namespace fibrenet::optimizer {

// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators",
// OOPSLA 2014): a 64-bit state advanced by a Weyl increment and scrambled by a finaliser.
// Good enough for sampling and for deriving independent seeds; not cryptographic.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

  // Uniform integer in [0, n), n > 0, without modulo bias (rejection sampling).
  std::uint64_t Below(std::uint64_t n) {
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    std::uint64_t x = Next();
    while (x >= limit) x = Next();
    return x % n;
  }

 private:
  std::uint64_t state_;
};

// A seed derived from (seed, stream): different streams give independent generators.
inline std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t stream) {
  SplitMix64 mix(seed ^ (0xD1B54A32D192ED03ULL * (stream + 1)));
  return mix.Next();
}

}  // namespace fibrenet::optimizer
