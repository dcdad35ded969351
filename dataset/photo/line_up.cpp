#include "dataset/photo/line_up.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/util/quantile.h"

namespace lc2wf {
namespace {

constexpr double kTolDeg = 10.0;
constexpr size_t kMaxCandidates = 400;  // the longest lines propose directions: bounded work on any map
constexpr size_t kMaxDirections = 5;     // dominant directions looked for (bounded work: at most 15 candidates)
constexpr double kMinDirectionShare = 0.04;

struct Dir {
  Vec3 d;
  double w;  // length
};

// The direction that the most line length of `dirs` lies within kTolDeg of (the longest lines propose),
// refined by the principal direction of those lines; zero when `dirs` is empty.
Vec3 dominant(const std::vector<Dir>& dirs, double* length) {
  const double cos_tol = std::cos(kTolDeg * M_PI / 180);
  std::vector<size_t> order(dirs.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  const size_t proposals = std::min(order.size(), kMaxCandidates);
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(proposals), order.end(),
                    [&](size_t a, size_t b) { return dirs[a].w > dirs[b].w; });
  double best = -1;
  Vec3 best_d = Vec3::Zero();
  for (size_t c = 0; c < proposals; ++c) {
    const Vec3& cand = dirs[order[c]].d;
    double score = 0;
    for (const Dir& x : dirs) score += std::abs(x.d.dot(cand)) > cos_tol ? x.w : 0.0;
    if (score > best) best = score, best_d = cand;
  }
  *length = std::max(best, 0.0);
  if (best < 0) return Vec3::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Dir& x : dirs)
    if (std::abs(x.d.dot(best_d)) > cos_tol) scatter += x.w * x.d * x.d.transpose();
  const Vec3 v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  return v.dot(best_d) < 0 ? Vec3(-v) : v;
}

// Up to kMaxDirections dominant directions, each after the first holding at least kMinDirectionShare of the
// length: the most common first, then the most common among the lines not yet within kTolDeg of one found.
std::vector<Vec3> dominant_directions(std::vector<Dir> dirs) {
  const double cos_tol = std::cos(kTolDeg * M_PI / 180);
  double total = 0;
  for (const Dir& x : dirs) total += x.w;
  std::vector<Vec3> found;
  while (found.size() < kMaxDirections && !dirs.empty()) {
    double length = 0;
    const Vec3 d = dominant(dirs, &length);
    if (!found.empty() && length < kMinDirectionShare * total) break;
    found.push_back(d);
    std::erase_if(dirs, [&](const Dir& x) { return std::abs(x.d.dot(d)) > cos_tol; });
  }
  return found;
}

// The dominant directions and the normal of each pair more than 30 deg apart, without repeats (within 5 deg).
std::vector<Vec3> up_candidates(const std::vector<Vec3>& dominant) {
  std::vector<Vec3> all = dominant;
  for (size_t i = 0; i < dominant.size(); ++i)
    for (size_t j = i + 1; j < dominant.size(); ++j) {
      const Vec3 n = dominant[i].cross(dominant[j]);
      if (n.norm() > 0.5) all.push_back(n.normalized());
    }
  const double same = std::cos(5.0 * M_PI / 180);
  std::vector<Vec3> out;
  for (const Vec3& c : all)
    if (std::none_of(out.begin(), out.end(), [&](const Vec3& o) { return std::abs(o.dot(c)) > same; })) out.push_back(c);
  return out;
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

// The segments turned so that `up` is z.
std::vector<Segment3> turned_up(const std::vector<Segment3>& segments, const Vec3& up) {
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(up, Vec3::UnitZ()).toRotationMatrix();
  std::vector<Segment3> out(segments.size());
  for (size_t i = 0; i < segments.size(); ++i) out[i] = {R * segments[i].a, R * segments[i].b};
  return out;
}

}  // namespace

LineUp up_from_lines(const std::vector<Segment3>& segments, const HeightModel* model) {
  std::vector<Dir> dirs;
  for (const Segment3& s : segments) {
    const double len = s.length();
    if (len > 1e-12 && std::isfinite(len)) dirs.push_back({(s.b - s.a) / len, len});
  }
  if (dirs.empty()) throw std::invalid_argument("up_from_lines: no line with a length");
  const std::vector<Vec3> candidates = up_candidates(dominant_directions(dirs));
  LineUp r;
  for (const Vec3& c : candidates) r.tried.push_back({c, perpendicular_share(dirs, c), -1});
  size_t pick = 0;  // the candidate taken as the (unsigned) up
  std::optional<LineStatistics> chosen;  // the lines' statistics with `up` as z
  if (model) {
    std::vector<std::tuple<double, size_t, LineStatistics>> scored;
    for (size_t c = 0; c < candidates.size(); ++c) {
      try {
        LineStatistics st = line_statistics(turned_up(segments, candidates[c]));
        const double d = model->neighbour_distance(st);
        r.tried[c].distance = d;
        scored.emplace_back(d, c, std::move(st));
      } catch (const std::invalid_argument&) {  // no height this way up (a flat map seen edge-on): not the up
      }
    }
    std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b)); });
    if (!scored.empty()) {
      pick = std::get<1>(scored[0]), r.by_statistics = true, r.distance = std::get<0>(scored[0]);
      chosen = std::move(std::get<2>(scored[0]));
      if (scored.size() > 1) {
        r.runner_up_distance = std::get<0>(scored[1]);
        r.runner_up = candidates[std::get<1>(scored[1])];
        r.uncertain = r.runner_up_distance - r.distance < kUncertainUpMargin * r.distance;
      }
    }
  }
  if (!r.by_statistics)
    for (size_t c = 1; c < r.tried.size(); ++c)
      if (r.tried[c].perpendicular_share > r.tried[pick].perpendicular_share) pick = c;
  Vec3 up = candidates[pick];
  r.perpendicular_share = r.tried[pick].perpendicular_share;
  // The sign: as the nearest training clouds' ends say, else the wider end at the bottom. The chosen
  // statistics already hold log(bottom / top spread); without them the map is turned once more to measure it.
  double log_spread_ratio = 0;
  if (chosen) {
    log_spread_ratio = chosen->ends[0];
  } else {
    const std::vector<Segment3> upright = turned_up(segments, up);
    std::vector<double> z;
    for (const Segment3& s : upright) z.push_back(s.a.z()), z.push_back(s.b.z());
    log_spread_ratio = log_end_spread_ratio(upright, quantile(z, 0.01), quantile(z, 0.99));
  }
  r.spread_ratio = std::exp(std::abs(log_spread_ratio));
  const std::optional<bool> flipped = chosen ? model->upside_down(*chosen) : std::nullopt;
  r.sign_by_statistics = flipped.has_value();
  if (flipped ? *flipped : log_spread_ratio < 0) up = -up;
  r.up = up;
  return r;
}

}  // namespace lc2wf
