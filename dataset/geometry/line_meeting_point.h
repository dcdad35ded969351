// Normal equations of the point closest, in least squares, to a set of 3D lines (Σ |(I − uuᵀ)(X − p)|²),
// optionally pulled towards a prior point. Shared by junction refinement and the camera aim point.
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct LineMeetingPoint {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();

  // The line through `point` with unit direction `u`, counted `weight` times.
  void add_line(const Vec3& point, const Vec3& u, double weight = 1.0) {
    const Eigen::Matrix3d P = weight * (Eigen::Matrix3d::Identity() - u * u.transpose());
    A += P;
    b += P * point;
  }
  void add_prior(const Vec3& point, double weight) {
    A += weight * Eigen::Matrix3d::Identity();
    b += weight * point;
  }
};

}  // namespace lc2wf
