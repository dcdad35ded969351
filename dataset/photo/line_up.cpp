#include "dataset/photo/line_up.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {
namespace {

constexpr double kTolDeg = 10.0;
constexpr size_t kMaxCandidates = 400;  // the longest lines propose directions: bounded work on any map

struct Dir {
  Vec3 d;
  double w;  // length
};

// The direction (among the candidates' and restricted to those `allowed`) that the most line length
// lies within kTolDeg of, refined by the principal direction of those lines.
template <typename Allowed>
Vec3 dominant(const std::vector<Dir>& dirs, Allowed allowed) {
  const double cos_tol = std::cos(kTolDeg * M_PI / 180);
  std::vector<size_t> order(dirs.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(std::min(order.size(), kMaxCandidates)), order.end(),
                    [&](size_t a, size_t b) { return dirs[a].w > dirs[b].w; });
  double best = -1;
  Vec3 best_d = Vec3::Zero();
  for (size_t c = 0; c < std::min(order.size(), kMaxCandidates); ++c) {
    const Vec3& cand = dirs[order[c]].d;
    if (!allowed(cand)) continue;
    double score = 0;
    for (const Dir& x : dirs) score += std::abs(x.d.dot(cand)) > cos_tol ? x.w : 0.0;
    if (score > best) best = score, best_d = cand;
  }
  if (best < 0) return Vec3::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Dir& x : dirs)
    if (std::abs(x.d.dot(best_d)) > cos_tol) scatter += x.w * x.d * x.d.transpose();
  const Vec3 v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  return v.dot(best_d) < 0 ? Vec3(-v) : v;
}

double perpendicular_share(const std::vector<Dir>& dirs, const Vec3& axis) {
  const double sin_tol = std::sin(kTolDeg * M_PI / 180);
  double perp = 0, total = 0;
  for (const Dir& x : dirs) {
    total += x.w;
    if (std::abs(x.d.dot(axis)) < sin_tol) perp += x.w;
  }
  return total > 0 ? perp / total : 0.0;
}

// sqrt(det) of the 2D covariance, in the plane perpendicular to `up`, of the endpoints in the end slab.
double end_spread(const std::vector<Segment3>& segments, const Vec3& up, bool top) {
  std::vector<double> h;
  for (const Segment3& s : segments) h.push_back(s.a.dot(up)), h.push_back(s.b.dot(up));
  std::vector<double> sorted = h;
  std::sort(sorted.begin(), sorted.end());
  const double lo = sorted[sorted.size() / 100], hi = sorted[sorted.size() - 1 - sorted.size() / 100];
  const double cut = top ? hi - 0.15 * (hi - lo) : lo + 0.15 * (hi - lo);
  const Vec3 e1 = up.unitOrthogonal(), e2 = up.cross(e1);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> pts;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b}) {
      const double z = p.dot(up);
      if (top ? z >= cut : z <= cut) pts.emplace_back(p.dot(e1), p.dot(e2));
    }
  if (pts.size() < 3) return 0.0;
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  cov /= static_cast<double>(pts.size());
  return std::sqrt(std::max(0.0, cov.determinant()));
}

}  // namespace

LineUp up_from_lines(const std::vector<Segment3>& segments) {
  std::vector<Dir> dirs;
  for (const Segment3& s : segments) {
    const double len = s.length();
    if (len > 1e-12 && std::isfinite(len)) dirs.push_back({(s.b - s.a) / len, len});
  }
  if (dirs.empty()) throw std::invalid_argument("up_from_lines: no line with a length");
  LineUp r;
  const double sin_tol = std::sin(kTolDeg * M_PI / 180);
  r.axes[0] = dominant(dirs, [](const Vec3&) { return true; });
  Vec3 second = dominant(dirs, [&](const Vec3& d) { return std::abs(d.dot(r.axes[0])) < sin_tol; });
  if (second.norm() < 0.5) second = r.axes[0].unitOrthogonal();  // every line parallel: any perpendicular
  r.axes[1] = (second - second.dot(r.axes[0]) * r.axes[0]).normalized();
  r.axes[2] = r.axes[0].cross(r.axes[1]);
  int best = 0;
  double share[3];
  for (int a = 0; a < 3; ++a) {
    share[a] = perpendicular_share(dirs, r.axes[a]);
    if (share[a] > share[best]) best = a;
  }
  r.perpendicular_share = share[best];
  r.runner_up_share = 0;
  for (int a = 0; a < 3; ++a)
    if (a != best) r.runner_up_share = std::max(r.runner_up_share, share[a]);
  Vec3 up = r.axes[best];
  const double top = end_spread(segments, up, true), bottom = end_spread(segments, up, false);
  if (top > bottom) up = -up;
  r.spread_ratio = std::max(top, bottom) / std::max(std::min(top, bottom), 1e-12);
  r.up = up;
  return r;
}

}  // namespace lc2wf
