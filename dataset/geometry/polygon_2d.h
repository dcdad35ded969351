// Plane polygon operations the procedural buildings are assembled with: clipping a convex polygon by a
// half-plane, subtracting one convex polygon from another, and the outline of a set of polygons that tile a
// region of one plane (so coplanar pieces become one face with exactly the corners a person would draw).
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

using Polygon2 = std::vector<Vec2>;  // counter-clockwise, no repeated closing vertex

double signed_area(const Polygon2& p);

// Keeps the part of convex `p` where a*x + b*y + c >= -tol (a, b of unit length make tol a distance).
Polygon2 clip_half_plane(const Polygon2& p, double a, double b, double c, double tol = 1e-9);

// Convex `p` minus convex `cut`: convex pieces covering p \ cut (pieces smaller than min_area dropped).
std::vector<Polygon2> subtract_convex(const Polygon2& p, const Polygon2& cut, double min_area = 1e-10);

// Outline loops of the union of polygons that meet edge to edge or along parts of edges (a tiling of a
// region, no overlaps): shared stretches cancel, points closer than `tol` are one point. Outer loops come
// out counter-clockwise, holes clockwise; loops touching at a point are kept apart.
std::vector<Polygon2> union_outline(const std::vector<Polygon2>& tiles, double tol = 1e-7);

// The same, but a polygon face cannot carry a hole: each hole is joined to the rest of the outline by two
// bridges between existing corners (the shortest that stay inside and cross nothing), so a courtyard's
// base becomes two faces and no new point is made. Throws std::logic_error when no such bridges exist.
std::vector<Polygon2> union_outline_without_holes(const std::vector<Polygon2>& tiles, double tol = 1e-7);

}  // namespace lc2wf
