// Two-view line geometry used by the line triangulator: fundamental matrix, epipolar overlap of a source
// segment with a target segment, and ray-plane depths of a segment pair.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// F with x_b^T F x_a = 0 for pixels x_a in view a and x_b in view b of the same 3D point.
Eigen::Matrix3d fundamental_matrix(const Camera& a, const Camera& b);

// Unit world-frame ray through a pixel.
Vec3 pixel_ray(const Camera& camera, const Vec2& pixel);

// Intersection-over-union, along the target segment's line, of the target segment and the interval cut
// out of that line by the epipolar lines of the source endpoints. 0 when they do not touch, when an
// epipolar line is parallel to the target line or when the union is shorter than 1 px.
double epipolar_overlap(const Eigen::Matrix3d& F, const Segment2& source, const Segment2& target);

// Depths (Euclidean distances along the unit source rays ray1/ray2 from centre_a) at which the rays meet
// the plane through centre_b with unit normal `normal`. Empty when a ray is within `min_sin` (sine of the
// ray-plane angle) of being parallel to the plane.
std::optional<Eigen::Vector2d> ray_plane_depths(const Vec3& centre_a, const Vec3& ray1, const Vec3& ray2,
                                                const Vec3& centre_b, const Vec3& normal, double min_sin);

// Depths along the source rays src1/src2 (unit, from centre_a) of a segment whose 3D line lies in an
// epipolar plane, where the two views' planes coincide and ray_plane_depths has no intersection: each
// source endpoint ray is met with the target endpoint ray (unit, from centre_b) at the same place in the
// order along the line (both cameras see such a line from one side), at the rays' closest approach.
// Empty when a paired ray is within `min_sin` of parallel to its partner or a point lies behind a camera.
std::optional<Eigen::Vector2d> endpoint_depths(const Vec3& centre_a, const Vec3& src1, const Vec3& src2, const Vec3& centre_b,
                                               const Vec3& tgt1, const Vec3& tgt2, double min_sin);

}  // namespace lc2wf
