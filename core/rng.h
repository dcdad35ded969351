// Counter-based random numbers: element i of draw n depends only on (seed, n, i), so results are the
// same at any thread count and a saved (seed, counter) pair resumes the exact stream.
#pragma once

#include <cstdint>

namespace lc2wf {

class Rng {
 public:
  explicit Rng(uint64_t seed = 0x5eed) : seed_(seed) {}

  uint64_t seed() const { return seed_; }
  uint64_t counter() const { return counter_; }
  void set_state(uint64_t seed, uint64_t counter) { seed_ = seed, counter_ = counter; }

  // Reserves `count` consecutive draws and returns the index of the first; use with bits()/uniform().
  uint64_t reserve(uint64_t count) {
    uint64_t first = counter_;
    counter_ += count;
    return first;
  }
  // 64 random bits for draw index n (stateless, thread-safe).
  uint64_t bits(uint64_t n) const { return mix(seed_ * 0x9E3779B97F4A7C15ull + mix(n)); }
  // Uniform in [0, 1) for draw index n, 24 bits (exact in float).
  float uniform_f(uint64_t n) const { return static_cast<float>(bits(n) >> 40) * 0x1.0p-24f; }
  double uniform(uint64_t n) const { return static_cast<double>(bits(n) >> 11) * 0x1.0p-53; }

  // Sequential convenience draws (advance the counter by one).
  double next_uniform() { return uniform(reserve(1)); }
  double next_uniform(double lo, double hi) { return lo + (hi - lo) * next_uniform(); }
  double next_normal();  // Box-Muller, two draws
  uint64_t next_below(uint64_t n) { return n == 0 ? 0 : bits(reserve(1)) % n; }

 private:
  // splitmix64 finaliser: a strong 64-bit mixer.
  static uint64_t mix(uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint64_t seed_;
  uint64_t counter_ = 0;
};

}  // namespace lc2wf
