// Per-segment labels (f, i1, d1, i2, d2) of a line cloud against its GT wireframe.
//  - label_by_support: the 2D route. GT edges are projected into every support view (with a depth test
//    against the mesh), each supporting 2D segment votes for the projected GT edge it lies on, and the
//    3D segment gets that edge when enough supports and views agree.
//  - label_by_geometry: the pure-3D fallback for clouds without support lists (distance + angle +
//    overlap against the GT edges).
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct SupportLabelOptions {
  double pixel_tol = 3.0;          // px: both 2D endpoints within this of the projected GT edge's line
  double angle_tol_deg = 10.0;     // 2D angle; short supports need it (0.5 px noise on 10 px is ~4 deg)
  double min_overlap = 0.5;        // fraction of the support's length inside the visible part of the edge
  double min_vote_fraction = 0.5;  // of the segment's supports that must vote for the same edge
  int min_views = 2;               // distinct views among those votes
  int visibility_samples = 32;     // depth-tested samples per GT edge and view
  double depth_tolerance_m = 0.02; // a face this close in front of the edge point does not hide it
  void Check() const;
};

std::vector<SegmentLabel> label_by_support(const LineCloud& cloud, const PolyMesh& mesh,
                                           const SupportLabelOptions& options = {});

struct GeometricLabelOptions {
  double max_distance_m = 0.15;  // both endpoints within this of the GT edge's line (smallest vAP eta)
  double angle_tol_deg = 10.0;   // short noisy segments need slack: 3 cm noise on 0.4 m is ~6 deg
  double min_overlap = 0.5;      // fraction of the segment's length projecting inside the GT edge
  void Check() const;
};

std::vector<SegmentLabel> label_by_geometry(const std::vector<Segment3>& segments, const Wireframe& wireframe,
                                            const GeometricLabelOptions& options = {});

// Visible parts of a GT edge in one view, as intervals of the 2D parameter u along the projected edge
// (pixel(u) = p0 + u (p1 - p0)); empty when the edge is hidden or behind the camera.
struct ProjectedEdge {
  Vec2 p0, p1;
  std::vector<std::array<double, 2>> visible;
};
class MeshOccluder;
ProjectedEdge project_edge(const Camera& camera, const Vec3& a, const Vec3& b, const MeshOccluder& occluder,
                           int samples, double depth_tolerance);

}  // namespace lc2wf
