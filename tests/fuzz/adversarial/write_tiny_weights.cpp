// lc2wf-adversarial-weights DIR: writes the tiny junction + edge model pair of tests/common/tiny_weights.h,
// the weights folder the adversarial cases run lc2wf-infer, lc2wf-eval and lc2wf-reconstruct with.
#include <cstdio>
#include <exception>

#include "tests/common/tiny_weights.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lc2wf-adversarial-weights DIR\n");
    return 2;
  }
  try {
    lc2wf::test::write_tiny_weights(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-adversarial-weights: %s\n", e.what());
    return 1;
  }
  return 0;
}
