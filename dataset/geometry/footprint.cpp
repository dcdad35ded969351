#include "dataset/geometry/footprint.h"

#include <algorithm>
#include <limits>

namespace lc2wf {

std::vector<Vec2> convex_hull_xy(const std::vector<Vec3>& points) {
  std::vector<Vec2> p;
  for (const Vec3& v : points) p.push_back(v.head<2>());
  if (p.size() < 2) return p;
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
  if (hull.size() == 2 && hull[0] == hull[1]) hull.pop_back();
  return hull;
}

std::vector<Vec2> footprint_rectangle(const std::vector<Vec3>& points) {
  const std::vector<Vec2> hull = convex_hull_xy(points);
  if (hull.size() < 2) return {};
  double best_area = std::numeric_limits<double>::infinity();
  std::vector<Vec2> best;
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
      best = {a0 * u + b0 * n, a1 * u + b0 * n, a1 * u + b1 * n, a0 * u + b1 * n};
    }
  }
  return best;
}

std::pair<double, double> footprint_sides(const std::vector<Vec3>& points) {
  const std::vector<Vec2> r = footprint_rectangle(points);
  if (r.empty()) return {0.0, 0.0};
  const double u = (r[1] - r[0]).norm(), v = (r[2] - r[1]).norm();
  return {std::max(u, v), std::min(u, v)};
}

}  // namespace lc2wf
