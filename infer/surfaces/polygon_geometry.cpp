#include "infer/surfaces/polygon_geometry.h"

#include <algorithm>
#include <cmath>

namespace lc2wf {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Where p lies relative to the directed line ab: > 0 left, < 0 right (scaled by |ab|).
double orient(const Vec2& a, const Vec2& b, const Vec2& p) { return cross2(b - a, p - a); }

bool inside_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

// Sutherland-Hodgman: the part of `subject` left of every side of the counter-clockwise convex `clip`.
std::vector<Vec2> clip_convex(std::vector<Vec2> subject, const std::array<Vec2, 3>& clip) {
  for (int k = 0; k < 3 && !subject.empty(); ++k) {
    const Vec2 &a = clip[k], &b = clip[(k + 1) % 3];
    std::vector<Vec2> out;
    for (size_t i = 0; i < subject.size(); ++i) {
      const Vec2 &p = subject[i], &q = subject[(i + 1) % subject.size()];
      const double dp = orient(a, b, p), dq = orient(a, b, q);
      if (dp >= 0) out.push_back(p);
      if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    subject = std::move(out);
  }
  return subject;
}

}  // namespace

Vec3 newell_normal(const std::vector<Vec3>& polygon) {
  Vec3 n = Vec3::Zero();
  if (polygon.empty()) return n;
  const Vec3 c = polygon.front();  // relative coordinates keep far-from-origin frames exact
  for (size_t i = 0; i < polygon.size(); ++i) n += (polygon[i] - c).cross(polygon[(i + 1) % polygon.size()] - c);
  return n;
}

double polygon_area(const std::vector<Vec3>& polygon) { return 0.5 * newell_normal(polygon).norm(); }

double plane_angle_deg(const Vec3& a, const Vec3& b) {
  const double c = std::min(1.0, std::abs(a.normalized().dot(b.normalized())));
  return std::acos(c) * 180.0 / M_PI;
}

std::vector<Vec2> PlaneFrame::to_2d(const std::vector<Vec3>& points) const {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(to_2d(p));
  return out;
}

PlaneFrame plane_frame(const Vec3& normal, const Vec3& origin) {
  PlaneFrame f;
  f.origin = origin;
  f.normal = normal.normalized();
  // The axis least aligned with the normal gives a well-conditioned first direction.
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(f.normal(i)) < std::abs(f.normal(k))) k = i;
  const Vec3 axis = Vec3::Unit(k);
  f.u = (axis - f.normal * f.normal.dot(axis)).normalized();
  f.v = f.normal.cross(f.u);
  return f;
}

double signed_area(const std::vector<Vec2>& polygon) {
  double a = 0;
  for (size_t i = 0; i < polygon.size(); ++i) a += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * a;
}

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2 &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double eps) {
  const double lab = (b - a).norm(), lcd = (d - c).norm();
  if (lab < eps || lcd < eps) return false;
  const auto shared = [&](const Vec2& p) { return (p - a).norm() < eps || (p - b).norm() < eps; };
  // Distance from a point to a closed segment.
  const auto dist = [](const Vec2& p, const Vec2& s, const Vec2& e) {
    const Vec2 d = e - s;
    const double t = std::clamp((p - s).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (s + t * d - p).norm();
  };
  const double o1 = orient(a, b, c) / lab, o2 = orient(a, b, d) / lab;
  const double o3 = orient(c, d, a) / lcd, o4 = orient(c, d, b) / lcd;
  if (((o1 > eps && o2 < -eps) || (o1 < -eps && o2 > eps)) && ((o3 > eps && o4 < -eps) || (o3 < -eps && o4 > eps))) return true;
  // Touches: an endpoint of one on the other, unless it is an endpoint both share.
  if (!shared(c) && dist(c, a, b) < eps) return true;
  if (!shared(d) && dist(d, a, b) < eps) return true;
  const auto shared_cd = [&](const Vec2& p) { return (p - c).norm() < eps || (p - d).norm() < eps; };
  if (!shared_cd(a) && dist(a, c, d) < eps) return true;
  if (!shared_cd(b) && dist(b, c, d) < eps) return true;
  // Collinear overlap beyond a shared endpoint.
  if (std::abs(o1) < eps && std::abs(o2) < eps) {
    const Vec2 dir = (b - a) / lab;
    const double s0 = 0, s1 = lab, t0 = dir.dot(c - a), t1 = dir.dot(d - a);
    const double lo = std::max(s0, std::min(t0, t1)), hi = std::min(s1, std::max(t0, t1));
    if (hi - lo > eps) return true;
  }
  return false;
}

bool polygon_self_intersects(const std::vector<Vec2>& poly, double eps) {
  const size_t n = poly.size();
  if (n < 3) return true;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if ((poly[i] - poly[j]).norm() < eps) return true;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent sides meet at their shared vertex only; folding back on each other is an overlap.
        const size_t s = (i == 0 && j == n - 1) ? 0 : j;  // shared vertex
        const Vec2& p = poly[s];
        const Vec2& q1 = poly[(s + n - 1) % n];
        const Vec2& q2 = poly[(s + 1) % n];
        const Vec2 d1 = q1 - p, d2 = q2 - p;
        if (std::abs(cross2(d1, d2)) < eps * std::max(d1.norm(), d2.norm()) && d1.dot(d2) > 0) return true;
        continue;
      }
      if (segments_cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n], eps)) return true;
    }
  }
  return false;
}

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& polygon) {
  std::vector<std::array<int, 3>> out;
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return out;
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  if (signed_area(polygon) < 0) std::reverse(idx.begin(), idx.end());
  while (idx.size() > 3) {
    const int m = static_cast<int>(idx.size());
    bool clipped = false;
    for (int k = 0; k < m && !clipped; ++k) {
      const int ia = idx[(k + m - 1) % m], ib = idx[k], ic = idx[(k + 1) % m];
      const Vec2 &a = polygon[ia], &b = polygon[ib], &c = polygon[ic];
      if (orient(a, b, c) <= 0) continue;  // reflex or collinear: not an ear
      bool empty = true;
      for (int j = 0; j < m && empty; ++j) {
        const int ij = idx[j];
        if (ij == ia || ij == ib || ij == ic) continue;
        if (inside_triangle(polygon[ij], a, b, c)) empty = false;
      }
      if (!empty) continue;
      out.push_back({ia, ib, ic});
      idx.erase(idx.begin() + k);
      clipped = true;
    }
    if (!clipped) {
      // Collinear vertices hold no area: drop one; otherwise (not simple) fan out what is left.
      for (int k = 0; k < m && !clipped; ++k) {
        const Vec2 &a = polygon[idx[(k + m - 1) % m]], &b = polygon[idx[k]], &c = polygon[idx[(k + 1) % m]];
        if (std::abs(orient(a, b, c)) <= 1e-12 * std::max(1.0, (c - a).squaredNorm())) {
          out.push_back({idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]});
          idx.erase(idx.begin() + k);
          clipped = true;
        }
      }
      if (!clipped) {
        for (size_t k = 1; k + 1 < idx.size(); ++k) out.push_back({idx[0], idx[k], idx[k + 1]});
        return out;
      }
    }
  }
  out.push_back({idx[0], idx[1], idx[2]});
  return out;
}

double intersection_area(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const auto ta = triangulate_polygon(a), tb = triangulate_polygon(b);
  double area = 0;
  for (const auto& t : ta) {
    const std::vector<Vec2> subject{a[t[0]], a[t[1]], a[t[2]]};
    if (signed_area(subject) <= 0) continue;
    for (const auto& s : tb) {
      const std::array<Vec2, 3> clip{b[s[0]], b[s[1]], b[s[2]]};
      if (orient(clip[0], clip[1], clip[2]) <= 0) continue;
      const std::vector<Vec2> piece = clip_convex(subject, clip);
      if (piece.size() >= 3) area += std::abs(signed_area(piece));
    }
  }
  return area;
}

double polygon_iou(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const double aa = std::abs(signed_area(a)), ab = std::abs(signed_area(b));
  if (aa <= 0 || ab <= 0) return 0;
  const double inter = std::min(intersection_area(a, b), std::min(aa, ab));
  return inter / (aa + ab - inter);
}

}  // namespace lc2wf
