#include "infer/point_nms.h"

#include "dataset/point_nms.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace lc2wf {

std::vector<int> point_nms(const std::vector<Vec3>& points, const std::vector<double>& confidences, double radius,
                           PointNmsRule rule) {
  if (points.size() != confidences.size())
    throw std::invalid_argument("point_nms: " + std::to_string(points.size()) + " points but " +
                                std::to_string(confidences.size()) + " confidences");
  if (rule == PointNmsRule::kSuppressor) return suppressor_nms(points, confidences, radius);
  const int n = static_cast<int>(points.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return confidences[a] > confidences[b]; });
  const double r2 = radius * radius;
  auto close = [&](int a, int b) { return (points[a] - points[b]).squaredNorm() < r2; };

  std::vector<char> dropped(n, 0);
  for (int oi = 0; oi < n; ++oi) {
    const int j = order[oi];
    if (dropped[j]) continue;
    for (int ok = oi + 1; ok < n; ++ok)
      if (!dropped[order[ok]] && close(j, order[ok])) dropped[order[ok]] = 1;
  }
  std::vector<int> kept;
  for (int j : order)
    if (!dropped[j]) kept.push_back(j);
  return kept;
}

}  // namespace lc2wf
