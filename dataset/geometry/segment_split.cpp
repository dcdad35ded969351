#include "dataset/geometry/segment_split.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/formats/errors.h"
#include "dataset/geometry/segment_overlap.h"

namespace lc2wf {
namespace {

// Pieces of one chain (1 = the segment stays whole); capped so a huge length cannot overflow.
int64_t pieces_of(const Segment3& s, double max_length_m) {
  return std::max<int64_t>(1, static_cast<int64_t>(std::ceil(std::min(s.length() / max_length_m, 1e12) - 1e-9)));
}

void append_chains(const Segment3& s, int64_t n, std::vector<Segment3>& out) {
  const Vec3 step = (s.b - s.a) / static_cast<double>(n);
  const auto at = [&](double t) { return t >= static_cast<double>(n) ? s.b : Vec3(s.a + t * step); };
  for (int64_t k = 0; k < n; ++k) out.push_back({at(static_cast<double>(k)), at(static_cast<double>(k + 1))});
  out.push_back({s.a, at(0.5)});
  for (int64_t k = 0; k + 1 < n; ++k) out.push_back({at(k + 0.5), at(k + 1.5)});
  out.push_back({at(n - 0.5), s.b});
}

}  // namespace

void append_staggered_pieces(const Segment3& s, double max_length_m, std::vector<Segment3>& out) {
  const int64_t n = pieces_of(s, max_length_m);
  if (n == 1) out.push_back(s);
  else append_chains(s, n, out);
}

LineCloud split_long_segments(const LineCloud& cloud, double max_length_m) {
  if (!std::isfinite(max_length_m)) throw std::invalid_argument("split_long_segments: max_length_m must be finite");
  if (max_length_m <= 0.0) return cloud;
  int64_t total = 0;
  for (const Segment3& s : cloud.segments) {
    const int64_t n = pieces_of(s, max_length_m);
    total += n == 1 ? 1 : 2 * n + 1;
  }
  // Memory stays bounded whatever the cloud's extent (a 1 km line at 5 cm is 40,000 pieces).
  if (total > kMaxSplitSegments)
    throw DataError(cloud.name.empty() ? "line cloud" : cloud.name,
                    "cutting its segments into pieces of " + std::to_string(max_length_m) + " m would make " +
                        std::to_string(total) + " segments (limit " + std::to_string(kMaxSplitSegments) +
                        "): is the cloud in metres?");
  LineCloud out;
  out.name = cloud.name;
  out.cameras = cloud.cameras;
  out.wireframe = cloud.wireframe;
  out.units = cloud.units;
  out.external_line_map = cloud.external_line_map;
  out.segments.reserve(static_cast<size_t>(total));
  for (const Segment3& s : cloud.segments) append_staggered_pieces(s, max_length_m, out.segments);
  return out;
}

double overlapped_long_fraction(const LineCloud& cloud, double min_length_m) {
  const SegmentOverlapIndex index(cloud.segments, kMaxSplitSegments);
  std::vector<int> along;
  int64_t long_segments = 0, overlapped = 0;
  for (size_t i = 0; i < cloud.segments.size(); ++i) {
    if (cloud.segments[i].length() <= min_length_m) continue;
    ++long_segments;
    index.runs_along(i, along);
    overlapped += !along.empty();
  }
  return long_segments == 0 ? 1.0 : static_cast<double>(overlapped) / static_cast<double>(long_segments);
}

}  // namespace lc2wf
