#include "dataset/geometry/plane_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace lc2wf {

Plane fit_plane(const std::vector<Vec3>& points) {
  Plane plane;
  if (points.empty()) return plane;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) cov += (p - mean) * (p - mean).transpose();
  if (points.size() >= 3) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    // Two large eigenvalues are needed for a plane; a line's points leave the normal undetermined.
    if (eig.eigenvalues()(1) > 1e-12 * std::max(1.0, eig.eigenvalues()(2))) plane.normal = eig.eigenvectors().col(0).normalized();
  }
  plane.offset = plane.normal.dot(mean);
  return plane;
}

}  // namespace lc2wf
