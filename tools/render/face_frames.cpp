#include "tools/render/face_frames.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

bool point_in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = cross2(b - a, p - a), d2 = cross2(c - b, p - b), d3 = cross2(a - c, p - c);
  return d1 >= 0 && d2 >= 0 && d3 >= 0;
}

// Newell's method: robust normal of a planar (possibly non-convex) polygon.
Vec3 newell_normal(const std::vector<Vec3>& pts) {
  Vec3 n = Vec3::Zero();
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec3& a = pts[i];
    const Vec3& b = pts[(i + 1) % pts.size()];
    n.x() += (a.y() - b.y()) * (a.z() + b.z());
    n.y() += (a.z() - b.z()) * (a.x() + b.x());
    n.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return n;
}

FaceFrame make_frame(const std::vector<Vec3>& pts, FaceLabel label) {
  FaceFrame f;
  Vec3 n = newell_normal(pts);
  const double len = n.norm();
  f.normal = len > 0 ? Vec3(n / len) : Vec3::UnitZ();
  f.origin = pts.front();
  f.offset = f.normal.dot(f.origin);
  const double nz = std::abs(f.normal.z());
  if (label == FaceLabel::Base) {
    f.kind = SurfaceKind::Base;
  } else if (nz > 0.985) {
    f.kind = label == FaceLabel::Roof ? SurfaceKind::FlatRoof : SurfaceKind::Base;
  } else if (label == FaceLabel::Roof && nz > 0.1) {
    f.kind = SurfaceKind::SlopedRoof;
  } else {
    f.kind = SurfaceKind::Wall;
  }
  if (nz > 0.985) {
    f.axis_u = Vec3::UnitX();
    f.axis_v = Vec3::UnitY();
  } else {
    f.axis_u = f.normal.cross(Vec3::UnitZ()).normalized();  // horizontal line in the plane
    f.axis_v = f.normal.cross(f.axis_u).normalized();
    if (f.axis_v.z() > 0) f.axis_v = -f.axis_v;  // point down the slope
  }
  return f;
}

}  // namespace

std::vector<std::array<int, 3>> ear_clip(const std::vector<Vec2>& poly) {
  std::vector<std::array<int, 3>> tris;
  const int n = static_cast<int>(poly.size());
  if (n < 3) return tris;
  double area = 0;
  for (int i = 0; i < n; ++i) area += cross2(poly[i], poly[(i + 1) % n]);
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = area >= 0 ? i : n - 1 - i;  // counter-clockwise order
  int guard = 0;
  while (idx.size() > 3 && guard < 4 * n * n) {
    ++guard;
    bool clipped = false;
    const int m = static_cast<int>(idx.size());
    for (int k = 0; k < m; ++k) {
      const int ia = idx[(k + m - 1) % m], ib = idx[k], ic = idx[(k + 1) % m];
      const Vec2 &a = poly[ia], &b = poly[ib], &c = poly[ic];
      if (cross2(b - a, c - b) <= 0) continue;  // reflex or degenerate corner
      bool contains = false;
      for (int j : idx) {
        if (j == ia || j == ib || j == ic) continue;
        if (point_in_triangle(poly[j], a, b, c)) {
          contains = true;
          break;
        }
      }
      if (contains) continue;
      tris.push_back({ia, ib, ic});
      idx.erase(idx.begin() + k);
      clipped = true;
      break;
    }
    // Degenerate input (collinear runs, self-touching): fall back to a fan over what remains.
    if (!clipped) break;
  }
  for (size_t k = 1; k + 1 < idx.size(); ++k) tris.push_back({idx[0], idx[k], idx[k + 1]});
  return tris;
}

FacedMesh build_faced_mesh(const PolyMesh& mesh) {
  if (mesh.faces.empty()) throw std::invalid_argument("mesh has no faces");
  if (!mesh.labels.empty() && mesh.labels.size() != mesh.faces.size())
    throw std::invalid_argument("mesh has " + std::to_string(mesh.labels.size()) + " labels for " +
                                std::to_string(mesh.faces.size()) + " faces");
  FacedMesh out;
  out.vertices = mesh.vertices;
  out.box_min = Vec3::Constant(1e300);
  out.box_max = Vec3::Constant(-1e300);
  for (const Vec3& v : mesh.vertices) {
    out.box_min = out.box_min.cwiseMin(v);
    out.box_max = out.box_max.cwiseMax(v);
  }
  const int nv = static_cast<int>(mesh.vertices.size());
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const auto& face = mesh.faces[fi];
    if (face.size() < 3) throw std::invalid_argument("face " + std::to_string(fi) + " has fewer than 3 vertices");
    std::vector<Vec3> pts;
    for (int v : face) {
      if (v < 0 || v >= nv) throw std::invalid_argument("face " + std::to_string(fi) + " has bad vertex id " + std::to_string(v));
      pts.push_back(mesh.vertices[v]);
    }
    const FaceLabel label = mesh.labels.empty() ? FaceLabel::Wall : mesh.labels[fi];
    FaceFrame frame = make_frame(pts, label);
    // Golden-ratio sequence: distinct, deterministic offsets per face index.
    frame.texture_offset = Vec2(std::fmod(fi * 0.6180339887, 1.0) * 7.3, std::fmod(fi * 0.7548776662, 1.0) * 5.9);
    // Project onto two axes orthogonal to the normal, keeping orientation consistent with it.
    const Vec3 a = frame.normal.unitOrthogonal();
    const Vec3 b = frame.normal.cross(a);
    std::vector<Vec2> flat;
    for (const Vec3& p : pts) flat.emplace_back((p - frame.origin).dot(a), (p - frame.origin).dot(b));
    for (const auto& t : ear_clip(flat))
      out.triangles.push_back({{face[t[0]], face[t[1]], face[t[2]]}, static_cast<int>(fi)});
    out.frames.push_back(frame);
  }
  return out;
}

}  // namespace lc2wf
