// Per-view quantities the triangulator reuses across every pair: camera centre, unit endpoint rays,
// the plane through the centre and each segment, and the depth-adaptive sigma factor.
#pragma once

#include <vector>

#include "tools/triangulation/line_triangulator.h"

namespace lc2wf {

struct ViewGeometry {
  const Camera* camera = nullptr;
  const std::vector<Segment2>* segments = nullptr;
  Vec3 centre = Vec3::Zero();
  std::vector<Vec3> ray_a, ray_b, ray_mid;  // unit world rays through the endpoints and the midpoint
  std::vector<Vec3> plane_normal;           // unit normal of the plane (centre, ray_a, ray_b)
  double sigma_factor = 0.0;                // sin of the angle that sigma_p pixels subtend at the principal point
};

ViewGeometry make_view_geometry(const TriangulationView& view, double sigma_p_px);

// A 3D hypothesis for one source segment from one match.
struct LineHypothesis {
  int source_segment = 0;
  int target_view = 0;
  int target_segment = 0;
  double overlap = 0.0;
  double depth1 = 0.0, depth2 = 0.0;  // along the source rays
  Vec3 p1 = Vec3::Zero(), p2 = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();     // unit, p2 - p1
  double target_var1 = 0.0, target_var2 = 0.0;  // (sigma of the target view at p1/p2)^2
  bool by_endpoints = false;  // the pair lies in an epipolar plane: depths from endpoint_depths
};

// Matches every segment of view a against view b (directed); results sorted by (source, rank).
std::vector<LineHypothesis> match_view_pair(const ViewGeometry& a, const ViewGeometry& b, int b_index,
                                            const TriangulatorOptions& options, long long* candidate_tests);

// Per-view drop-out counts (see TriangulationStats).
struct ScoreCounts {
  long long with_hypothesis = 0, with_two_views = 0, scored = 0, kept = 0;
};

// Scores the hypotheses of one source view (all target views, grouped by source segment) and returns
// the confirmed best hypothesis per segment, with supports.
std::vector<TriangulatedLine> score_view(int view_index, int num_segments, const std::vector<LineHypothesis>& hypotheses,
                                         const ViewGeometry& view, const TriangulatorOptions& options,
                                         ScoreCounts* counts = nullptr);

}  // namespace lc2wf
