// The robust similarity fit (dataset/photo/similarity_align.h): exact on exact points, GPS-like noise and a
// wild fix left out, and points on one line refused.
#include "dataset/photo/similarity_align.h"

#include <gtest/gtest.h>

#include "core/rng.h"

namespace lc2wf {
namespace {

Similarity some_similarity() {
  Similarity s;
  s.scale = 7.3;
  s.R = Eigen::AngleAxisd(1.1, Vec3(0.2, 0.5, -0.7).normalized()).toRotationMatrix();
  s.t = Vec3(30, -12, 4);
  return s;
}

// A drone orbit: 16 centres on a circle of radius 3 (SfM units) with a little height variation.
std::vector<Vec3> orbit() {
  std::vector<Vec3> p;
  for (int k = 0; k < 16; ++k) p.emplace_back(3 * std::cos(k * 0.39), 3 * std::sin(k * 0.39), 0.2 * std::sin(k * 1.3));
  return p;
}

TEST(SimilarityAlign, ExactPointsGiveTheSimilarity) {
  const Similarity truth = some_similarity();
  const std::vector<Vec3> src = orbit();
  std::vector<Vec3> dst;
  for (const Vec3& p : src) dst.push_back(truth.apply(p));
  const SimilarityFit fit = fit_similarity(src, dst);
  EXPECT_NEAR(fit.transform.scale, truth.scale, 1e-9);
  EXPECT_LT((fit.transform.R - truth.R).norm(), 1e-9);
  EXPECT_LT(fit.rms_residual, 1e-9);
  EXPECT_EQ(fit.inliers.size(), src.size());
  // The spread of the fixes the residual is judged against: the source's RMS distance from its mean, scaled.
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : src) mean += p / static_cast<double>(src.size());
  double spread = 0;
  for (const Vec3& p : src) spread += (p - mean).squaredNorm() / static_cast<double>(src.size());
  EXPECT_NEAR(fit.dst_spread, truth.scale * std::sqrt(spread), 1e-9);
}

TEST(SimilarityAlign, NoisyFixesAndOneWildFix) {
  const Similarity truth = some_similarity();
  const std::vector<Vec3> src = orbit();
  std::vector<Vec3> dst;
  Rng rng(7);
  for (const Vec3& p : src) dst.push_back(truth.apply(p) + Vec3(rng.next_uniform(-1, 1), rng.next_uniform(-1, 1), rng.next_uniform(-2, 2)));
  dst[5] += Vec3(60, 0, 0);  // a fix from before the receiver settled
  const SimilarityFit fit = fit_similarity(src, dst, {.outlier_factor = 3, .outlier_floor = 5, .rounds = 3});
  EXPECT_EQ(fit.inliers.size(), src.size() - 1);
  EXPECT_NEAR(fit.transform.scale / truth.scale, 1.0, 0.05);
  EXPECT_LT(fit.rms_residual, 2.5);
  const Vec3 up = fit.transform.R.transpose() * Vec3::UnitZ(), true_up = truth.R.transpose() * Vec3::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up.dot(true_up))) * 180 / M_PI, 3.0);
}

TEST(SimilarityAlign, PointsOnOneLineOrTooFewAreRefused) {
  std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_THROW(fit_similarity(line, line), std::invalid_argument);
  EXPECT_THROW(fit_similarity({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(fit_similarity(orbit(), {{0, 0, 0}}), std::invalid_argument);
  SimilarityFitOptions bad;
  bad.rounds = 0;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
