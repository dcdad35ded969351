#include "infer/junction_refine.h"

#include <stdexcept>
#include <string>

namespace lc2wf {

void JunctionRefineOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("JunctionRefineOptions." + what); };
  if (!(radius >= 0)) fail("radius must be >= 0");
  if (min_segments < 2) fail("min_segments must be >= 2");
  if (!(prior_weight > 0)) fail("prior_weight must be > 0");
  if (!(min_length >= 0)) fail("min_length must be >= 0");
}

std::vector<Vec3> refine_junctions(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const JunctionRefineOptions& options) {
  options.Check();
  std::vector<Vec3> out = junctions;
  if (options.radius == 0) return out;
  const double r2 = options.radius * options.radius;
  for (Vec3& J : out) {
    // Normal equations of sum_i w_i |(I - d_i d_iᵀ)(X - p_i)|² + prior |X - J|², w_i = 1 per line.
    Eigen::Matrix3d A = options.prior_weight * Eigen::Matrix3d::Identity();
    Vec3 b = options.prior_weight * J;
    int used = 0;
    for (const Segment3& s : segments) {
      const Vec3 d = s.b - s.a;
      const double len = d.norm();
      if (len < options.min_length) continue;
      if ((s.a - J).squaredNorm() > r2 && (s.b - J).squaredNorm() > r2) continue;
      const Vec3 u = d / len;
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
      A += P;
      b += P * s.a;
      ++used;
    }
    if (used < options.min_segments) continue;
    const Vec3 X = A.ldlt().solve(b);
    if (X.allFinite() && (X - J).squaredNorm() <= r2) J = X;
  }
  return out;
}

}  // namespace lc2wf
