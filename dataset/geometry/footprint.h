// The size of a building's footprint, one rule for every statistic that reports it.
#pragma once

#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Long and short side of the minimum-area rectangle around the points' x/y (over the convex hull's edge
// directions). {0, 0} for fewer than two distinct points.
std::pair<double, double> footprint_sides(const std::vector<Vec3>& points);

}  // namespace lc2wf
