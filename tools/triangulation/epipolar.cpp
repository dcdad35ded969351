#include "tools/triangulation/epipolar.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace lc2wf {

Eigen::Matrix3d fundamental_matrix(const Camera& a, const Camera& b) {
  const Eigen::Matrix3d R = b.R * a.R.transpose();
  const Vec3 t = b.t - R * a.t;
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  return b.K.inverse().transpose() * tx * R * a.K.inverse();
}

Vec3 pixel_ray(const Camera& camera, const Vec2& pixel) {
  const Vec3 m((pixel.x() - camera.K(0, 2) - camera.K(0, 1) * (pixel.y() - camera.K(1, 2)) / camera.K(1, 1)) / camera.K(0, 0),
               (pixel.y() - camera.K(1, 2)) / camera.K(1, 1), 1.0);
  return (camera.R.transpose() * m).normalized();
}

double epipolar_overlap(const Eigen::Matrix3d& F, const Segment2& source, const Segment2& target) {
  const Vec3 q1(target.a.x(), target.a.y(), 1.0), q2(target.b.x(), target.b.y(), 1.0);
  const Vec3 l = q1.cross(q2).normalized();
  const Vec3 e1 = (F * Vec3(source.a.x(), source.a.y(), 1.0)).normalized();
  const Vec3 e2 = (F * Vec3(source.b.x(), source.b.y(), 1.0)).normalized();
  const Vec3 x1 = l.cross(e1), x2 = l.cross(e2);
  if (std::abs(x1.z()) < 1e-12 || std::abs(x2.z()) < 1e-12) return 0.0;
  const Vec2 d = target.b - target.a;
  const double len = d.norm();
  if (len <= 0) return 0.0;
  const Vec2 u = d / len;
  // Positions along the target line, target segment = [0, len].
  double s1 = (x1.head<2>() / x1.z() - target.a).dot(u);
  double s2 = (x2.head<2>() / x2.z() - target.a).dot(u);
  if (s1 > s2) std::swap(s1, s2);
  if (s2 < 0 || s1 > len) return 0.0;
  const double outer = std::max(s2, len) - std::min(s1, 0.0);
  if (outer < 1.0) return 0.0;
  const double inner = std::min(s2, len) - std::max(s1, 0.0);
  return std::max(0.0, inner) / outer;
}

std::optional<Eigen::Vector2d> ray_plane_depths(const Vec3& centre_a, const Vec3& ray1, const Vec3& ray2,
                                                const Vec3& centre_b, const Vec3& normal, double min_sin) {
  const double c1 = normal.dot(ray1), c2 = normal.dot(ray2);
  if (std::abs(c1) < std::max(min_sin, 1e-12) || std::abs(c2) < std::max(min_sin, 1e-12)) return std::nullopt;
  const double num = normal.dot(centre_b - centre_a);
  return Eigen::Vector2d(num / c1, num / c2);
}

namespace {

// Depth along ray (ca, ra) of its closest approach to ray (cb, rb); empty when the rays are within
// min_sin of parallel or the point lies behind either centre.
std::optional<double> closest_approach_depth(const Vec3& ca, const Vec3& ra, const Vec3& cb, const Vec3& rb, double min_sin) {
  const double c = ra.dot(rb), denom = 1.0 - c * c;
  if (denom < std::max(min_sin * min_sin, 1e-24)) return std::nullopt;
  const Vec3 w = ca - cb;
  const double d = ra.dot(w), e = rb.dot(w);
  const double la = (c * e - d) / denom, lb = (e - c * d) / denom;
  if (la <= 0 || lb <= 0) return std::nullopt;
  return la;
}

}  // namespace

std::optional<Eigen::Vector2d> endpoint_depths(const Vec3& centre_a, const Vec3& src1, const Vec3& src2, const Vec3& centre_b,
                                               const Vec3& tgt1, const Vec3& tgt2, double min_sin) {
  // The order along the line: the angle of a ray about the plane's normal, measured from the baseline.
  const Vec3 base = centre_b - centre_a;
  const Vec3 normal = src1.cross(src2);
  if (normal.norm() <= 0 || base.norm() <= 0) return std::nullopt;
  const Vec3 n = normal.normalized();
  const Vec3 in_plane = base - base.dot(n) * n;
  if (in_plane.norm() < 1e-12 * base.norm()) return std::nullopt;
  const Vec3 e1 = in_plane.normalized(), e2 = n.cross(e1);
  auto angle = [&](const Vec3& r) { return std::atan2(r.dot(e2), r.dot(e1)); };
  const bool same_order = (angle(src1) < angle(src2)) == (angle(tgt1) < angle(tgt2));
  const Vec3& partner1 = same_order ? tgt1 : tgt2;
  const Vec3& partner2 = same_order ? tgt2 : tgt1;
  const auto d1 = closest_approach_depth(centre_a, src1, centre_b, partner1, min_sin);
  const auto d2 = closest_approach_depth(centre_a, src2, centre_b, partner2, min_sin);
  if (!d1 || !d2) return std::nullopt;
  return Eigen::Vector2d(*d1, *d2);
}

}  // namespace lc2wf
