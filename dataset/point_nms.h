// The release's point NMS: a point is dropped when another point with strictly higher score lies closer
// than `radius` (strict <), or an equal-score point earlier in the order that is still alive does.
// This differs from greedy NMS on chains (A > B > C with A-B and B-C close: greedy keeps A and C, this
// keeps only A). Returns surviving indices sorted by descending score (ties: lower index first).
#pragma once

#include <vector>

#include "dataset/geometry.h"

namespace lc2wf {

std::vector<int> suppressor_nms(const std::vector<Vec3>& points, const std::vector<double>& scores, double radius);

}  // namespace lc2wf
