// Test scenes for the line triangulator: GT edges of a building projected into a camera ring, with
// hidden parts removed (depth test against the mesh) and optional seeded corruption.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/building.h"
#include "tools/triangulation/line_triangulator.h"

namespace lc2wf::test {

struct Corruption {
  double perpendicular_sigma_px = 0.0;  // endpoint noise across the segment
  double along_jitter_px = 0.0;         // endpoint jitter along the segment (uniform +-)
  double clutter_fraction = 0.0;        // random outlier segments, as a fraction of the true count
  uint64_t seed = 1;
};

// One segment per visible run of every GT edge in every view (runs shorter than 4 px are dropped);
// `edge_of` (optional) receives the GT edge id of each segment (-1 for clutter).
std::vector<TriangulationView> project_gt_segments(const Building& building, const std::vector<Camera>& cameras,
                                                   const Corruption& corruption = {},
                                                   std::vector<std::vector<int>>* edge_of = nullptr);

// Distance from p to the segment [a, b].
double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace lc2wf::test
