// The median of a sample: the middle value, or the mean of the two middle values of an even count; 0 for
// an empty sample (report fields stay numbers).
#pragma once

#include <algorithm>
#include <vector>

namespace lc2wf {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  if (v.size() % 2) return v[mid];
  return 0.5 * (*std::max_element(v.begin(), v.begin() + static_cast<long>(mid)) + v[mid]);
}

}  // namespace lc2wf
