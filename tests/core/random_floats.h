// Uniform floats in [-1, 1] from a seed: the operands of the GEMM tests.
#pragma once

#include <random>
#include <vector>

namespace lc2wf::test {

inline std::vector<float> random_floats(size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(n);
  for (float& x : v) x = u(gen);
  return v;
}

}  // namespace lc2wf::test
