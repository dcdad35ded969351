#include "dataset/selection/pair_support.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace lc2wf {

void PairSupportOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("PairSupportOptions." + what); };
  if (!(min_support >= 0 && min_support <= 1)) fail("min_support must be in [0, 1]");
  if (!(radius_m > 0) || !std::isfinite(radius_m)) fail("radius_m must be a positive distance in metres");
  if (!(max_angle_deg > 0 && max_angle_deg <= 90)) fail("max_angle_deg must be in (0, 90]");
  if (!(keep_shorter_than_m >= 0) || !std::isfinite(keep_shorter_than_m))
    fail("keep_shorter_than_m must be a distance >= 0 in metres");
}

SegmentsByX::SegmentsByX(const std::vector<Segment3>& segments) {
  for (const Segment3& s : segments) {
    const double length = s.length();
    if (length > 1e-9 && std::isfinite(length)) segments_.push_back(s);  // no direction to compare otherwise
  }
  const auto min_x = [](const Segment3& s) { return std::min(s.a.x(), s.b.x()); };
  std::stable_sort(segments_.begin(), segments_.end(), [&](const Segment3& p, const Segment3& q) { return min_x(p) < min_x(q); });
  for (const Segment3& s : segments_) min_x_.push_back(min_x(s)), max_x_extent_ = std::max(max_x_extent_, std::abs(s.b.x() - s.a.x()));
}

std::pair<size_t, size_t> SegmentsByX::meeting(double x_lo, double x_hi) const {
  const auto first = std::lower_bound(min_x_.begin(), min_x_.end(), x_lo - max_x_extent_);
  return {static_cast<size_t>(first - min_x_.begin()), static_cast<size_t>(std::upper_bound(first, min_x_.end(), x_hi) - min_x_.begin())};
}

SegmentSupport::SegmentSupport(const std::vector<Segment3>& segments) : by_x_(segments) {
  for (const Segment3& s : by_x_.segments()) {
    const double length = s.length();
    dir_.push_back((s.b - s.a) / length);
    length_.push_back(length);
  }
}

namespace {

// The one test of a support query: the span along u-v (in metres from u) of a segment whose ends relative
// to u are a and b and whose unit direction is dir, when it counts for the query's unit direction d.
bool counted_span(const Vec3& a, const Vec3& b, const Vec3& dir, const Vec3& d, double length, double min_cos, double r2,
                  std::pair<double, double>* span) {
  if (std::abs(dir.dot(d)) < min_cos) return false;
  const double ta = a.dot(d), tb = b.dot(d);
  if ((a - ta * d).squaredNorm() > r2 || (b - tb * d).squaredNorm() > r2) return false;
  const double lo = std::max(std::min(ta, tb), 0.0), hi = std::min(std::max(ta, tb), length);
  if (!(hi > lo)) return false;
  *span = {lo, hi};
  return true;
}

// The share of [0, length] the union of the spans covers (the spans are sorted here, so the order the
// segments were met in does not matter).
double covered_share(std::vector<std::pair<double, double>>& spans, double length) {
  std::sort(spans.begin(), spans.end());
  double covered = 0, lo = 0, hi = -1;
  for (const auto& [s0, s1] : spans) {
    if (s0 > hi) {
      if (hi > lo) covered += hi - lo;
      lo = s0;
      hi = s1;
    } else {
      hi = std::max(hi, s1);
    }
  }
  if (hi > lo) covered += hi - lo;
  return std::min(1.0, covered / length);
}

}  // namespace

double SegmentSupport::support(const Vec3& u, const Vec3& v, double radius_m, double max_angle_deg) const {
  const double length = (v - u).norm();
  if (!(length > 1e-9)) return 1.0;
  const Vec3 d = (v - u) / length;
  const double min_cos = std::cos(max_angle_deg * M_PI / 180.0), r2 = radius_m * radius_m;
  std::vector<std::pair<double, double>> spans;  // covered parameter ranges along u-v, in metres
  // A counted segment has a point within radius_m of u-v (it lies within radius_m of the line and overlaps
  // u-v along it), so its x range meets u-v's widened by radius_m.
  const auto [first, last] = by_x_.meeting(std::min(u.x(), v.x()) - radius_m, std::max(u.x(), v.x()) + radius_m);
  std::pair<double, double> span;
  for (size_t k = first; k < last; ++k) {
    const Vec3 a = by_x_.segments()[k].a - u, b = a + dir_[k] * length_[k];
    if (counted_span(a, b, dir_[k], d, length, min_cos, r2, &span)) spans.push_back(span);
  }
  return covered_share(spans, length);
}

AnchoredSegmentSupport::AnchoredSegmentSupport(const std::vector<Segment3>& segments, const Vec3& anchor) : anchor_(anchor) {
  // The same segments, directions and lengths SegmentSupport would hold, so the shares agree bit for bit.
  const SegmentSupport all(segments);
  for (size_t k = 0; k < all.by_x_.segments().size(); ++k) {
    const Vec3 a = all.by_x_.segments()[k].a - anchor;
    a_.push_back(a);
    b_.push_back(a + all.dir_[k] * all.length_[k]);
    for (int c = 0; c < 3; ++c) dir_xyz_[c].push_back(all.dir_[k][c]);
  }
}

double AnchoredSegmentSupport::support(const Vec3& v, double radius_m, double max_angle_deg) const {
  const double length = (v - anchor_).norm();
  if (!(length > 1e-9)) return 1.0;
  const Vec3 d = (v - anchor_) / length;
  const double min_cos = std::cos(max_angle_deg * M_PI / 180.0), r2 = radius_m * radius_m;
  // Most segments point elsewhere: a loop the compiler vectorises screens them (with a margin for its
  // rounding), and the one test decides for the rest.
  // Each thread's scratch is kept, to spare a query its allocations.
  thread_local std::vector<double> cosines;
  thread_local std::vector<std::pair<double, double>> spans;
  const size_t n = a_.size();
  cosines.resize(n);
  const double* x = dir_xyz_[0].data();
  const double* y = dir_xyz_[1].data();
  const double* z = dir_xyz_[2].data();
  double* cosine = cosines.data();
  for (size_t k = 0; k < n; ++k) cosine[k] = std::abs(x[k] * d.x() + y[k] * d.y() + z[k] * d.z());
  const double screen = min_cos - 1e-9;
  spans.clear();
  std::pair<double, double> span;
  for (size_t k = 0; k < n; ++k)
    if (cosine[k] >= screen && counted_span(a_[k], b_[k], Vec3(x[k], y[k], z[k]), d, length, min_cos, r2, &span))
      spans.push_back(span);
  return covered_share(spans, length);
}

std::vector<JunctionPair> supported_pairs(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                          const PairSupportOptions& options) {
  if (!options.enabled()) return pairs;
  const SegmentSupport support(segments);
  std::vector<JunctionPair> out;
  for (const JunctionPair& p : pairs)
    if ((p.v - p.u).norm() < options.keep_shorter_than_m ||
        support.support(p.u, p.v, options.radius_m, options.max_angle_deg) >= options.min_support)
      out.push_back(p);
  return out;
}

}  // namespace lc2wf
