#include "dataset/photo/line_confirmation.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "dataset/geometry/segment_overlap.h"

namespace lc2wf {

void LineConfirmationOptions::Check() const {
  if (min_other_views < 0 || min_other_views > 1000)
    throw std::invalid_argument("LineConfirmationOptions.min_other_views must be in [0, 1000], got " + std::to_string(min_other_views));
}

std::vector<int> confirming_views(const LineCloud& cloud) {
  const size_t n = cloud.segments.size();
  if (cloud.support.size() != n)
    throw std::invalid_argument("line cloud '" + cloud.name + "' has no 2D supports: its lines' source views are unknown");
  std::vector<int> source(n);
  for (size_t i = 0; i < n; ++i) {
    if (cloud.support[i].empty())
      throw std::invalid_argument("line cloud '" + cloud.name + "': segment " + std::to_string(i) + " has no 2D support");
    source[i] = cloud.support[i].front().view;
  }
  // Overlap in either direction: a short fragment on a long line confirms it, and the long line the fragment.
  const SegmentOverlapIndex index(cloud.segments);
  std::vector<std::vector<int>> views(n);
  std::vector<int> along;
  for (size_t i = 0; i < n; ++i) {
    index.runs_along(i, along);
    for (int j : along) {
      const auto k = static_cast<size_t>(j);
      if (source[k] == source[i]) continue;
      views[i].push_back(source[k]);
      views[k].push_back(source[i]);
    }
  }
  std::vector<int> count(n);
  for (size_t i = 0; i < n; ++i) {
    std::sort(views[i].begin(), views[i].end());
    count[i] = static_cast<int>(std::unique(views[i].begin(), views[i].end()) - views[i].begin());
  }
  return count;
}

LineCloud keep_confirmed_lines(const LineCloud& cloud, const LineConfirmationOptions& options) {
  options.Check();
  const bool supported = cloud.support.size() == cloud.segments.size() &&
                         std::none_of(cloud.support.begin(), cloud.support.end(), [](const auto& s) { return s.empty(); });
  if (options.min_other_views == 0 || !supported) return cloud;
  const std::vector<int> count = confirming_views(cloud);
  std::vector<bool> keep(count.size());
  for (size_t i = 0; i < count.size(); ++i) keep[i] = count[i] >= options.min_other_views;
  return keep_segments(cloud, keep);
}

}  // namespace lc2wf
