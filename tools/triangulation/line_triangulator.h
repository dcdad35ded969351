// Multi-view 3D line triangulation with Line3D++-equivalent semantics (our own implementation): visual
// neighbours from the known cameras, epipolar-overlap matching of 2D segments, ray-plane triangulation,
// cross-view scoring with depth-adaptive position and angle regularisers, and the best hypothesis per 2D
// segment kept together with the 2D segments that support it. The result is the dense, redundant line
// cloud LC2WF learns from. Parallel over source views; the output does not depend on the thread count.
#pragma once

#include <optional>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "tools/triangulation/view_neighbours.h"

namespace lc2wf {

struct TriangulatorOptions {
  NeighbourOptions neighbours;
  double epipolar_overlap = 0.25;       // min intersection-over-union along the target line
  int knn = 10;                         // candidates kept per source segment and target view (<= 0: all)
  double min_ray_plane_angle_deg = 1.0; // a source ray this close to the target plane (or, matched by
                                        // endpoints, to the target's endpoint ray) gives unstable depth
  // A target segment within this angle of the epipolar line through it lies in the epipolar plane, where
  // the two segments' planes coincide (a facade's horizontals seen by cameras walking along it): such a
  // pair is triangulated from its endpoints (endpoint_depths) when the target lies within 2 sigma_p_px of
  // the source endpoints' epipolar lines. 0: never (Line3D++ loses these lines).
  double endpoint_angle_deg = 2.0;
  double min_view_angle_deg = 5.625;    // 3D direction vs the ray through the source midpoint (pi/32)
  double sigma_p_px = 2.5;              // positional regulariser, pixels (depth adaptive)
  double sigma_a_deg = 10.0;            // angular regulariser
  double min_similarity = 0.5;          // pairwise hypothesis similarity counts only above this
  // Line3D++'s 0.75 (one confirming view suffices): 1.7-2x the lines of 1.0 (LIMAP's fullscore_th, two
  // confirming views) and +4/+6 points GT-edge coverage (raster/Blender, tools/README.md); the labels
  // then need 3 voting views to keep f=1 lines as accurate (CloudBuilderOptions).
  double min_best_score = 0.75;         // a 2D segment gets a 3D line only above this score
  double min_score_fraction = 0.1;      // ... and above this fraction of its view's best score
  // Endpoint depths of a kept line: similarity-weighted mean over the best hypothesis and the agreeing
  // hypotheses of the other views (Line3D++ keeps the best pair's depths, which carry one pair's noise).
  bool average_depths = true;
  void Check() const;
};

struct TriangulationView {
  Camera camera;
  std::vector<Segment2> segments;
};

struct SegmentRef {
  int view = 0;
  int segment = 0;
};

struct SupportingSegment {
  SegmentRef ref;
  double similarity = 1.0;  // 1 for the source and its partner
};

// One record per 2D segment that has a confirmed best hypothesis.
struct TriangulatedLine {
  Segment3 line;       // endpoints on the source segment's rays
  double score = 0.0;  // sum of the best agreeing similarities over other views
  bool by_endpoints = false;  // its best hypothesis came from endpoints (a line in the epipolar plane)
  SegmentRef source;
  // source first, then the best hypothesis's partner, then one segment per other agreeing view (view order).
  std::vector<SupportingSegment> support;
};

struct TriangulationStats {
  int views = 0;
  int directed_pairs = 0;
  long long candidate_tests = 0;  // (source, target) pairs that reached the exact overlap test
  long long hypotheses = 0;       // matches kept after kNN and the orientation filter
  // Where 2D segments drop out, summed over views: all, with >= 1 hypothesis, with hypotheses from >= 2
  // target views (needed for any score), with a best score > 0, and kept (above both thresholds).
  long long segments = 0;
  long long segments_with_hypothesis = 0;
  long long segments_with_two_views = 0;
  long long segments_scored = 0;
  long long segments_kept = 0;
  long long kept_by_endpoints = 0;  // of the kept ones, those whose best hypothesis came from endpoints
  double seconds_matching = 0.0;
  double seconds_scoring = 0.0;
};

// scene_centre: e.g. the building's box centre; when absent the optical axes' intersection is used.
// Throws std::invalid_argument for bad options or a view without a valid camera.
std::vector<TriangulatedLine> triangulate_lines(const std::vector<TriangulationView>& views, const TriangulatorOptions& options,
                                                const std::optional<Vec3>& scene_centre = std::nullopt,
                                                TriangulationStats* stats = nullptr);

}  // namespace lc2wf
