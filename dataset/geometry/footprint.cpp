#include "dataset/geometry/footprint.h"

#include <algorithm>
#include <limits>

namespace lc2wf {

std::pair<double, double> footprint_sides(const std::vector<Vec3>& points) {
  std::vector<Vec2> p;
  for (const Vec3& v : points) p.push_back(v.head<2>());
  if (p.size() < 2) return {0.0, 0.0};
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) { return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x(); };
  std::vector<Vec2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  double best_area = std::numeric_limits<double>::infinity(), lo_side = 0, hi_side = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 d = hull[(i + 1) % hull.size()] - hull[i];
    if (d.norm() <= 0) continue;
    const Vec2 u = d.normalized(), n(-u.y(), u.x());
    double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
    for (const Vec2& q : hull) {
      a0 = std::min(a0, u.dot(q)), a1 = std::max(a1, u.dot(q));
      b0 = std::min(b0, n.dot(q)), b1 = std::max(b1, n.dot(q));
    }
    if ((a1 - a0) * (b1 - b0) < best_area) {
      best_area = (a1 - a0) * (b1 - b0);
      hi_side = std::max(a1 - a0, b1 - b0);
      lo_side = std::min(a1 - a0, b1 - b0);
    }
  }
  return {hi_side, lo_side};
}

}  // namespace lc2wf
