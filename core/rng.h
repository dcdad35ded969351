// Counter-based random numbers: element i of draw n depends only on (seed, n, i), so results are the
// same at any thread count and a saved (seed, counter) pair resumes the exact stream.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

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
  // The buildings a forward pass computes when a batch is cut up (micro-batches, data-parallel ranks):
  // [first, first + count) of a batch of `total`, stacked outermost in every tensor the pass draws for.
  void set_batch_slice(uint64_t first, uint64_t count, uint64_t total) {
    if (count == 0 || first + count > total)
      throw std::invalid_argument("Rng::set_batch_slice: [" + std::to_string(first) + ", +" + std::to_string(count) +
                                  ") is not a slice of a batch of " + std::to_string(total));
    slice_first_ = first, slice_count_ = count, slice_total_ = total;
  }
  void clear_batch_slice() { slice_first_ = 0, slice_count_ = slice_total_ = 0; }

  struct TensorDraws {
    uint64_t first = 0;   // the block's first draw (its key)
    uint64_t offset = 0;  // index of this tensor's element 0 within the block
  };
  // Reserves the draws of a batch-major tensor of `count` elements. With a batch slice set, the block is
  // the one the whole batch's tensor would get and `offset` places the slice in it, so dropout masks do
  // not depend on how a batch is cut up. Without one it is reserve(count) at offset 0.
  TensorDraws reserve_tensor(uint64_t count) {
    if (slice_count_ == 0 || slice_count_ == slice_total_) return {reserve(count), 0};
    if (count % slice_count_ != 0)
      throw std::invalid_argument("Rng::reserve_tensor: " + std::to_string(count) + " elements are not " +
                                  std::to_string(slice_count_) + " equal buildings of a batch-major tensor");
    const uint64_t per_building = count / slice_count_, whole = per_building * slice_total_;
    // Sliced masks index the block with 32-bit lanes.
    if (whole >= (uint64_t{1} << 32)) throw std::invalid_argument("Rng::reserve_tensor: a batch tensor of 2^32 or more elements cannot be sliced");
    return {reserve(whole), per_building * slice_first_};
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
  uint64_t slice_first_ = 0, slice_count_ = 0, slice_total_ = 0;  // no slice: count 0
};

}  // namespace lc2wf
