#include "core/rng.h"

#include <cmath>

namespace lc2wf {

double Rng::next_normal() {
  uint64_t first = reserve(2);
  // 1 - u keeps the logarithm's argument in (0, 1].
  double u1 = 1.0 - uniform(first);
  double u2 = uniform(first + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace lc2wf
