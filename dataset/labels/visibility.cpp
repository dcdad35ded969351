#include "dataset/labels/visibility.h"

#include <cmath>

namespace lc2wf {
namespace {

Eigen::Vector2d drop(const Vec3& p, int axis) {
  return axis == 0 ? Eigen::Vector2d(p.y(), p.z()) : axis == 1 ? Eigen::Vector2d(p.x(), p.z()) : Eigen::Vector2d(p.x(), p.y());
}

// Even-odd rule; works for non-convex roof polygons.
bool inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x()) in = !in;
  }
  return in;
}

}  // namespace

MeshOccluder::MeshOccluder(const PolyMesh& mesh) {
  for (const auto& f : mesh.faces) {
    Face face;
    Vec3 n = Vec3::Zero(), c = Vec3::Zero();
    for (size_t k = 0; k < f.size(); ++k) {
      const Vec3& a = mesh.vertices[f[k]];
      const Vec3& b = mesh.vertices[f[(k + 1) % f.size()]];
      n += a.cross(b);
      c += a;
    }
    if (n.norm() == 0) continue;  // degenerate polygon hides nothing
    face.normal = n.normalized();
    face.offset = face.normal.dot(c / static_cast<double>(f.size()));
    face.normal.cwiseAbs().maxCoeff(&face.drop_axis);
    face.box_min = face.box_max = mesh.vertices[f[0]];
    for (int id : f) {
      face.polygon.push_back(drop(mesh.vertices[id], face.drop_axis));
      face.box_min = face.box_min.cwiseMin(mesh.vertices[id]);
      face.box_max = face.box_max.cwiseMax(mesh.vertices[id]);
    }
    faces_.push_back(std::move(face));
  }
}

bool MeshOccluder::occluded(const Vec3& eye, const Vec3& point, double tolerance) const {
  const Vec3 d = point - eye;
  const double len = d.norm();
  if (len <= tolerance) return false;
  const double t_max = 1.0 - tolerance / len;
  for (const auto& f : faces_) {
    const double denom = f.normal.dot(d);
    if (std::abs(denom) < 1e-12) continue;
    const double t = (f.offset - f.normal.dot(eye)) / denom;
    if (t <= 1e-9 || t >= t_max) continue;
    const Vec3 hit = eye + t * d;
    const double slack = 1e-9 + 1e-6 * len;
    if ((hit.array() < f.box_min.array() - slack).any() || (hit.array() > f.box_max.array() + slack).any()) continue;
    if (inside(f.polygon, drop(hit, f.drop_axis))) return true;
  }
  return false;
}

}  // namespace lc2wf
