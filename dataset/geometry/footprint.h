// The size of a building's footprint, one rule for every statistic that reports it.
#pragma once

#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Convex hull of the points' x/y, counter-clockwise, without collinear points (fewer than three points when
// they are collinear or fewer than three are distinct).
std::vector<Vec2> convex_hull_xy(const std::vector<Vec3>& points);

// Corners (counter-clockwise) of the minimum-area rectangle around the points' x/y, over the convex hull's
// edge directions; empty for fewer than two distinct points (two coincide when the points are collinear).
std::vector<Vec2> footprint_rectangle(const std::vector<Vec3>& points);

// Long and short side of the minimum-area rectangle around the points' x/y (over the convex hull's edge
// directions). {0, 0} for fewer than two distinct points.
std::pair<double, double> footprint_sides(const std::vector<Vec3>& points);

}  // namespace lc2wf
