#include "infer/surfaces/shell_checks.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/util/number_format.h"
#include "infer/surfaces/polygon_geometry.h"

namespace lc2wf {
namespace {

struct FaceGeometry {
  Plane plane;
  PlaneFrame frame;
  std::vector<Vec2> polygon;
  Vec3 lo, hi;  // bounding box
};

// Whether the 3D segment pq passes through the inside of face g away from its border (a crossing between faces).
bool segment_pierces(const Vec3& p, const Vec3& q, const FaceGeometry& g, double eps) {
  const double dp = g.plane.distance(p), dq = g.plane.distance(q);
  if ((dp > eps && dq > eps) || (dp < -eps && dq < -eps)) return false;
  if (std::abs(dp) <= eps && std::abs(dq) <= eps) return false;  // in the plane: the overlap test covers it
  if (std::abs(dp) <= eps || std::abs(dq) <= eps) return false;  // touches the plane at an end: a shared corner or side
  const Vec3 x = p + (q - p) * (dp / (dp - dq));
  const Vec2 x2 = g.frame.to_2d(x);
  if (!point_in_polygon(x2, g.polygon)) return false;
  for (size_t i = 0; i < g.polygon.size(); ++i) {
    const Vec2 &a = g.polygon[i], &b = g.polygon[(i + 1) % g.polygon.size()];
    const Vec2 d = b - a;
    const double t = std::clamp((x2 - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    if ((a + t * d - x2).norm() <= eps) return false;  // on the border
  }
  return true;
}

// For each vertex, the first vertex within `tol` of it (itself when none is).
std::vector<int> weld(const std::vector<Vec3>& v, double tol) {
  std::vector<int> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    out[i] = static_cast<int>(i);
    for (size_t j = 0; j < i; ++j)
      if (out[j] == static_cast<int>(j) && (v[i] - v[j]).norm() <= tol) {
        out[i] = static_cast<int>(j);
        break;
      }
  }
  return out;
}

}  // namespace

std::vector<std::string> ShellCheck::problems() const {
  std::vector<std::string> out;
  if (non_planar_faces > 0)
    out.push_back(std::to_string(non_planar_faces) + " face(s) not planar (up to " + format_number("%.3f", max_planarity_m) + " m off)");
  if (open_edges > 0) out.push_back(std::to_string(open_edges) + " edge(s) bound only one face");
  if (overused_edges > 0) out.push_back(std::to_string(overused_edges) + " edge(s) bound three or more faces");
  if (misoriented_edges > 0) out.push_back(std::to_string(misoriented_edges) + " edge(s) run the same way in both faces");
  else if (closed() && signed_volume <= 0) out.push_back("the shell encloses no positive volume");
  if (self_intersecting_faces > 0) out.push_back(std::to_string(self_intersecting_faces) + " face(s) not simple polygons");
  if (intersecting_face_pairs > 0) out.push_back(std::to_string(intersecting_face_pairs) + " pair(s) of faces intersect");
  return out;
}

ShellCheck check_shell(const SurfaceModel& m, double tol, WorkBudget* budget) {
  constexpr const char* kStep = "shell checks";
  ShellCheck c;
  std::vector<FaceGeometry> geo;
  const long vertices = static_cast<long>(m.vertices.size());
  long rings = 0;
  for (const SurfaceFace& f : m.faces) rings += static_cast<long>(f.ring.size() * f.ring.size());
  if (budget && !budget->charge(rings + vertices * (vertices - 1) / 2, kStep)) return c;  // ring tests, welding
  for (const SurfaceFace& f : m.faces) {
    const std::vector<Vec3> pts = m.polygon(f);
    FaceGeometry g;
    g.plane = fit_plane(pts);
    const Vec3 nn = newell_normal(pts);
    if (nn.norm() > 0 && nn.dot(g.plane.normal) < 0) g.plane = {-g.plane.normal, -g.plane.offset};
    g.frame = plane_frame(g.plane.normal, pts.empty() ? Vec3::Zero() : pts.front());
    g.polygon = g.frame.to_2d(pts);
    g.lo = g.hi = pts.empty() ? Vec3::Zero() : pts.front();
    double dev = 0;
    for (const Vec3& p : pts) {
      dev = std::max(dev, std::abs(g.plane.distance(p)));
      g.lo = g.lo.cwiseMin(p);
      g.hi = g.hi.cwiseMax(p);
    }
    c.max_planarity_m = std::max(c.max_planarity_m, dev);
    if (dev > tol) ++c.non_planar_faces;
    if (polygon_self_intersects(g.polygon, tol)) ++c.self_intersecting_faces;
    geo.push_back(std::move(g));
  }
  // Sides: how many faces use each, and in which directions. Vertices within the tolerance are one point (as a
  // file with rounded coordinates stores them), so two ids at one place cannot hide a side shared by 4 faces.
  const std::vector<int> point = weld(m.vertices, tol);
  std::map<std::pair<int, int>, std::pair<int, int>> sides;  // (min, max) -> (runs min->max, runs max->min)
  for (const SurfaceFace& f : m.faces)
    for (size_t i = 0; i < f.ring.size(); ++i) {
      const int a = point[f.ring[i]], b = point[f.ring[(i + 1) % f.ring.size()]];
      if (a == b) continue;  // a side shorter than the tolerance: the ring's simplicity check reports it
      auto& s = sides[{std::min(a, b), std::max(a, b)}];
      (a < b ? s.first : s.second) += 1;
    }
  for (const auto& [side, runs] : sides) {
    const int uses = runs.first + runs.second;
    if (uses == 1) ++c.open_edges;
    if (uses > 2) ++c.overused_edges;
    if (runs.first > 1 || runs.second > 1) ++c.misoriented_edges;
  }
  const Vec3 origin = m.vertices.empty() ? Vec3::Zero() : m.vertices.front();
  for (const SurfaceFace& f : m.faces)
    for (size_t i = 1; i + 1 < f.ring.size(); ++i)
      c.signed_volume += (m.vertices[f.ring[0]] - origin).dot((m.vertices[f.ring[i]] - origin).cross(m.vertices[f.ring[i + 1]] - origin)) / 6;
  // Face pairs: a side of one through the inside of the other, or two faces of one plane overlapping.
  for (size_t a = 0; a < m.faces.size(); ++a) {
    if (budget && !budget->charge(static_cast<long>(m.faces.size() - a), kStep)) return c;  // box tests
    for (size_t b = a + 1; b < m.faces.size(); ++b) {
      const FaceGeometry &ga = geo[a], &gb = geo[b];
      if ((ga.lo.array() > gb.hi.array() + tol).any() || (gb.lo.array() > ga.hi.array() + tol).any()) continue;
      // Each side of one face against the other's plane and polygon, or the overlap of two coplanar polygons.
      const long ra = static_cast<long>(m.faces[a].ring.size()), rb = static_cast<long>(m.faces[b].ring.size());
      if (budget && !budget->charge(2 * ra * rb + ra * ra + rb * rb, kStep)) return c;
      bool hit = false;
      if (plane_angle_deg(ga.plane.normal, gb.plane.normal) < 1 && std::abs(std::abs(ga.plane.offset) - std::abs(gb.plane.offset)) < tol &&
          std::abs(gb.plane.distance(m.vertices[m.faces[a].ring[0]])) < tol) {
        const std::vector<Vec2> pb = ga.frame.to_2d(m.polygon(m.faces[b]));
        hit = intersection_area(ga.polygon, pb) > tol * tol * 10;
      } else {
        for (int pass = 0; pass < 2 && !hit; ++pass) {
          const SurfaceFace& f = m.faces[pass == 0 ? a : b];
          const FaceGeometry& g = pass == 0 ? gb : ga;
          for (size_t i = 0; i < f.ring.size() && !hit; ++i)
            hit = segment_pierces(m.vertices[f.ring[i]], m.vertices[f.ring[(i + 1) % f.ring.size()]], g, tol);
        }
      }
      if (hit) ++c.intersecting_face_pairs;
    }
  }
  return c;
}

}  // namespace lc2wf
