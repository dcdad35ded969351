#include "dataset/selection/point_nms.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "dataset/geometry/spatial_grid.h"

namespace lc2wf {

std::vector<int> point_nms(const std::vector<Vec3>& points, const std::vector<double>& scores, double radius,
                           PointNmsRule rule) {
  if (points.size() != scores.size())
    throw std::invalid_argument("point_nms: " + std::to_string(points.size()) + " points but " +
                                std::to_string(scores.size()) + " scores");
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });
  if (!(radius > 0)) return order;
  const SpatialGrid grid(points, radius);
  std::vector<char> dropped(points.size(), 0);
  std::vector<int> near;
  for (int j : order) {
    if (dropped[j]) continue;
    grid.query_strict(points[j], radius, near);
    for (int i : near) {
      if (i == j) continue;
      if (rule == PointNmsRule::kGreedy) {
        // Only weaker points (later in the order) fall, and a fallen point never suppresses.
        if (scores[i] < scores[j] || (scores[i] == scores[j] && i > j)) dropped[i] = 1;
      } else if (scores[i] <= scores[j]) {
        dropped[i] = 1;
      } else {
        dropped[j] = 1;
      }
    }
  }
  std::vector<int> kept;
  for (int j : order)
    if (!dropped[j]) kept.push_back(j);
  return kept;
}

}  // namespace lc2wf
