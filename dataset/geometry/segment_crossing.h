// Whether two 3D segments cross: their closest points lie close together and away from every end. A
// building's edges meet only at junctions, so two predicted edges that cross cannot both be right
// (model/post_process.h, "crossing edges").
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// The closest points of segments [a0, a1] and [b0, b1]: a0 + s (a1 - a0) and b0 + t (b1 - b0), s and t in
// [0, 1], and their distance. A zero-length segment is its first point; parallel segments take s = 0 or the
// first t that clamps.
struct SegmentClosestPoints {
  double s = 0.0;
  double t = 0.0;
  double distance = 0.0;
};
SegmentClosestPoints segment_closest_points(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

// True when the segments come within `max_distance` of each other at points at least `end_margin` from all
// four ends (so edges that share or nearly share a junction, and an edge that ends on another, never
// cross), and their directions differ by more than `min_angle_deg` (near-parallel overlaps are line NMS's).
bool segments_cross(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double max_distance,
                    double end_margin, double min_angle_deg);

}  // namespace lc2wf
