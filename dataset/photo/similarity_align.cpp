#include "dataset/photo/similarity_align.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/util/median.h"

namespace lc2wf {

void SimilarityFitOptions::Check() const {
  if (!(outlier_factor == 0 || outlier_factor >= 1)) throw std::invalid_argument("SimilarityFitOptions.outlier_factor must be 0 or >= 1");
  if (!(outlier_floor >= 0) || !std::isfinite(outlier_floor)) throw std::invalid_argument("SimilarityFitOptions.outlier_floor must be >= 0");
  if (rounds < 1) throw std::invalid_argument("SimilarityFitOptions.rounds must be >= 1");
  if (!(min_spread_ratio > 0 && min_spread_ratio < 1)) throw std::invalid_argument("SimilarityFitOptions.min_spread_ratio must be in (0, 1)");
}

namespace {


// Second over first singular value of the centred points: ~0 for points on one line.
double spread_ratio(const std::vector<Vec3>& p, const std::vector<int>& ids) {
  Vec3 mean = Vec3::Zero();
  for (int k : ids) mean += p[k];
  mean /= static_cast<double>(ids.size());
  Eigen::Matrix3Xd c(3, ids.size());
  for (size_t k = 0; k < ids.size(); ++k) c.col(k) = p[ids[k]] - mean;
  const Vec3 sv = Eigen::JacobiSVD<Eigen::Matrix3Xd>(c).singularValues();
  return sv(0) > 0 ? sv(1) / sv(0) : 0.0;
}

}  // namespace

Similarity least_squares_similarity(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const std::vector<int>& ids) {
  Eigen::Matrix3Xd a(3, ids.size()), b(3, ids.size());
  for (size_t k = 0; k < ids.size(); ++k) a.col(k) = src[ids[k]], b.col(k) = dst[ids[k]];
  const Eigen::Matrix4d T = Eigen::umeyama(a, b, true);
  const Eigen::Matrix3d sR = T.topLeftCorner<3, 3>();
  Similarity s;
  s.scale = std::cbrt(sR.determinant());
  s.R = sR / s.scale;
  s.t = T.topRightCorner<3, 1>();
  return s;
}

SimilarityFit fit_similarity(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const SimilarityFitOptions& o) {
  o.Check();
  if (src.size() != dst.size()) throw std::invalid_argument("fit_similarity: " + std::to_string(src.size()) + " source points for " + std::to_string(dst.size()));
  if (src.size() < 3) throw std::invalid_argument("fit_similarity: " + std::to_string(src.size()) + " point(s), at least 3 needed");
  for (size_t k = 0; k < src.size(); ++k)
    if (!src[k].allFinite() || !dst[k].allFinite()) throw std::invalid_argument("fit_similarity: point " + std::to_string(k) + " is not finite");
  SimilarityFit fit;
  for (int k = 0; k < static_cast<int>(src.size()); ++k) fit.inliers.push_back(k);
  auto check_spread = [&](const std::vector<int>& ids) {
    if (spread_ratio(src, ids) < o.min_spread_ratio || spread_ratio(dst, ids) < o.min_spread_ratio)
      throw std::invalid_argument("fit_similarity: the " + std::to_string(ids.size()) + " points lie on one line: the rotation about it is unknown");
  };
  check_spread(fit.inliers);
  std::vector<double> residual(src.size());
  for (int round = 0;; ++round) {
    fit.transform = least_squares_similarity(src, dst, fit.inliers);
    for (size_t k = 0; k < src.size(); ++k) residual[k] = (fit.transform.apply(src[k]) - dst[k]).norm();
    fit.median_residual = median(residual);
    if (round + 1 >= o.rounds || o.outlier_factor == 0) break;
    const double limit = std::max(o.outlier_factor * fit.median_residual, o.outlier_floor);
    std::vector<int> keep;
    for (int k = 0; k < static_cast<int>(src.size()); ++k)
      if (residual[k] <= limit) keep.push_back(k);
    if (keep.size() == fit.inliers.size() || keep.size() < 3) break;
    check_spread(keep);
    fit.inliers = keep;
  }
  const double n = static_cast<double>(fit.inliers.size());
  Vec3 mean = Vec3::Zero();
  double sum = 0;
  for (int k : fit.inliers) sum += residual[k] * residual[k], mean += dst[k] / n;
  fit.rms_residual = std::sqrt(sum / n);
  double spread = 0;
  for (int k : fit.inliers) spread += (dst[k] - mean).squaredNorm() / n;
  fit.dst_spread = std::sqrt(spread);
  return fit;
}

}  // namespace lc2wf
