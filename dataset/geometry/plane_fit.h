// The least-squares plane through a set of points: the surfaces' face finder and shell checks
// (infer/surfaces/) and the flat-part test of photo wireframes (model/flat_parts.h) share it.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct Plane {
  Vec3 normal = Vec3::UnitZ();  // unit length
  double offset = 0;            // normal . x = offset on the plane
  double distance(const Vec3& p) const { return normal.dot(p) - offset; }
};

// Least-squares plane through the points (smallest principal direction); needs >= 3 points not all on a line
// for a meaningful normal (fewer: the z=const plane through their mean).
Plane fit_plane(const std::vector<Vec3>& points);

}  // namespace lc2wf
