// Planar polygon geometry shared by the face finder, the shell checks and the face metrics: 2D frames in a
// plane, areas, point-in-polygon, crossing tests, ear-clipping triangulation and the overlap (intersection over
// union) of two simple polygons; plane fits are dataset/geometry/plane_fit.h's.
#pragma once

#include <array>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/plane_fit.h"  // Plane, fit_plane

namespace lc2wf {

// Sum of cross products of consecutive vertices (Newell): normal direction times twice the polygon's area,
// well defined for non-convex and slightly non-planar polygons.
Vec3 newell_normal(const std::vector<Vec3>& polygon);
double polygon_area(const std::vector<Vec3>& polygon);
// Angle in degrees between two planes' normals, ignoring their sign (0-90).
double plane_angle_deg(const Vec3& a, const Vec3& b);

// An orthonormal 2D frame in a plane: (u, v, normal) right-handed, so a polygon that runs counter-clockwise
// around `normal` has positive signed area in 2D.
struct PlaneFrame {
  Vec3 origin = Vec3::Zero(), u = Vec3::UnitX(), v = Vec3::UnitY(), normal = Vec3::UnitZ();
  Vec2 to_2d(const Vec3& p) const { return {u.dot(p - origin), v.dot(p - origin)}; }
  std::vector<Vec2> to_2d(const std::vector<Vec3>& points) const;
};
PlaneFrame plane_frame(const Vec3& normal, const Vec3& origin);

double signed_area(const std::vector<Vec2>& polygon);
bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon);
// True when the closed segments ab and cd share a point farther than `eps` from the endpoints they have in
// common (a touch at a shared endpoint is no crossing; overlapping collinear segments cross).
bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double eps);
// True when two non-adjacent sides meet, or a vertex repeats (a ring must be a simple polygon).
bool polygon_self_intersects(const std::vector<Vec2>& polygon, double eps);

// Ear clipping of a simple polygon (either orientation; collinear vertices allowed): n - 2 triangles of
// vertex indices, counter-clockwise. A polygon that is not simple still gives n - 2 triangles (a fan where no
// ear is left), so callers that need exact areas check simplicity first.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& polygon);

// Area of the intersection of two simple polygons and their intersection over union (0 when either is
// degenerate): exact, from the triangles of both clipped against each other.
double intersection_area(const std::vector<Vec2>& a, const std::vector<Vec2>& b);
double polygon_iou(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

}  // namespace lc2wf
