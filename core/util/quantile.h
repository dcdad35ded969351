// The value at quantile q (0..1) of a sample by nearest rank (index round(q · (n − 1)) of the sorted
// values, so every result is one of the values); 0 for an empty sample (report fields stay numbers).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace lc2wf {

inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const double rank = std::round(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1));
  const auto k = static_cast<long>(rank);
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<size_t>(k)];
}

}  // namespace lc2wf
