#include "dataset/geometry/segment_overlap.h"

#include <algorithm>
#include <cmath>

namespace lc2wf {
namespace {

// The points' spacing: any spacing finds every segment (the query radius grows with it and the exact test
// decides); a wide one keeps the index small, since a cloud's segments are many and its queries few.
constexpr double kOverlapSpacingM = 0.25;

}  // namespace

bool midpoint_runs_along(const Segment3& s, const Segment3& other) {
  const double length = s.length(), other_length = other.length();
  if (!(other_length > 0.0) || !(length > 0.0)) return false;
  const Vec3 mid = 0.5 * (s.a + s.b), dir = (s.b - s.a) / length, other_dir = (other.b - other.a) / other_length;
  if (std::abs(dir.dot(other_dir)) < kOverlapMinCos) return false;
  const double t = other_dir.dot(mid - other.a);
  return t >= 0.0 && t <= other_length && (mid - other.a - t * other_dir).norm() <= kOverlapRadiusM;
}

SegmentOverlapIndex::Samples SegmentOverlapIndex::sample_along(const std::vector<Segment3>& segments, int64_t max_points) {
  double total_length = 0.0;
  for (const Segment3& s : segments) total_length += s.length();
  // Points close enough that a segment passing within kOverlapRadiusM of a midpoint has one within the radius.
  const double spacing = std::max(kOverlapSpacingM, total_length / static_cast<double>(std::max<int64_t>(1, max_points)));
  Samples out;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment3& s = segments[i];
    const int64_t n = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(s.length() / spacing)));
    for (int64_t k = 0; k <= n; ++k) {
      out.points.push_back(s.a + (s.b - s.a) * (static_cast<double>(k) / static_cast<double>(n)));
      out.owner.push_back(static_cast<int>(i));
    }
  }
  out.radius = std::hypot(kOverlapRadiusM, spacing / 2);
  return out;
}

SegmentOverlapIndex::SegmentOverlapIndex(const std::vector<Segment3>& segments, int64_t max_points)
    : segments_(segments), samples_(sample_along(segments, max_points)), grid_(samples_.points, samples_.radius) {}

void SegmentOverlapIndex::runs_along(size_t i, std::vector<int>& out) const {
  out.clear();
  const Segment3& s = segments_[i];
  std::vector<int> near;
  grid_.query(0.5 * (s.a + s.b), samples_.radius, near);
  for (int p : near) {
    const int j = samples_.owner[static_cast<size_t>(p)];
    if (static_cast<size_t>(j) != i) out.push_back(j);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  std::erase_if(out, [&](int j) { return !midpoint_runs_along(s, segments_[static_cast<size_t>(j)]); });
}

}  // namespace lc2wf
