// A tiny, fully specified pseudo-random generator (SplitMix64, Steele, Lea & Flood 2014) so that
// every "random" start vector, perturbation and test case is the same on every machine and
// standard library. std distributions are implementation-defined and must not be used.
#pragma once
#include <cstdint>

namespace offsetopt {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next_u64() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1): the top 53 bits as a fraction.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  // Uniform integer in [0, n) for n > 0 (the tiny modulo bias is irrelevant for tests and starts).
  std::uint64_t below(std::uint64_t n) { return next_u64() % n; }

 private:
  std::uint64_t state_;
};

}  // namespace offsetopt
