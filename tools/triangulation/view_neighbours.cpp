#include "tools/triangulation/view_neighbours.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {

void NeighbourOptions::Check() const {
  if (count < 1) throw std::invalid_argument("NeighbourOptions.count must be >= 1");
  if (min_angle_deg < 0 || max_angle_deg > 180 || min_angle_deg >= max_angle_deg)
    throw std::invalid_argument("NeighbourOptions.min/max_angle_deg must satisfy 0 <= min < max <= 180");
}

Vec3 optical_axes_centre(const std::vector<Camera>& cameras) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  for (const Camera& c : cameras) {
    const Vec3 d = c.R.row(2).transpose().normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    A += P;
    b += P * c.center();
  }
  if (cameras.size() < 2 || std::abs(A.determinant()) < 1e-12) {
    Vec3 mean = Vec3::Zero();
    for (const Camera& c : cameras) mean += c.center() + c.R.row(2).transpose();
    return cameras.empty() ? mean : Vec3(mean / static_cast<double>(cameras.size()));
  }
  return A.lu().solve(b);
}

std::vector<std::vector<int>> select_neighbours(const std::vector<Camera>& cameras, const Vec3& scene_centre,
                                                const NeighbourOptions& options) {
  options.Check();
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  const int n = static_cast<int>(cameras.size());
  std::vector<std::vector<int>> out(n);
  for (int a = 0; a < n; ++a) {
    const Vec3 da = (scene_centre - cameras[a].center()).normalized();
    const Vec3 axis_a = cameras[a].R.row(2).transpose();
    std::vector<std::pair<double, int>> cand;
    for (int b = 0; b < n; ++b) {
      if (b == a) continue;
      const Vec3 db = (scene_centre - cameras[b].center()).normalized();
      const double beta = std::acos(std::clamp(da.dot(db), -1.0, 1.0)) * kDeg;
      const double axis_angle = std::acos(std::clamp(axis_a.dot(cameras[b].R.row(2).transpose()), -1.0, 1.0)) * kDeg;
      if (beta < options.min_angle_deg || beta > options.max_angle_deg || axis_angle >= 90.0) continue;
      cand.emplace_back(std::abs(beta - options.preferred_angle_deg), b);
    }
    std::sort(cand.begin(), cand.end());
    for (size_t k = 0; k < cand.size() && static_cast<int>(k) < options.count; ++k) out[a].push_back(cand[k].second);
  }
  return out;
}

}  // namespace lc2wf
