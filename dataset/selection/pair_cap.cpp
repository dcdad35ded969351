#include "dataset/selection/pair_cap.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/util/parallel_items.h"

namespace lc2wf {

void PairCapOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("PairCapOptions." + what); };
  if (max_pairs < 0) fail("max_pairs must be >= 0 (0 = no cap)");
  if (max_pairs_per_junction < 0) fail("max_pairs_per_junction must be >= 0 (0 = no per-junction limit)");
  if (!(end_length_m > 0) || !std::isfinite(end_length_m)) fail("end_length_m must be a positive distance in metres");
}

namespace {

double point_segment_distance(const Vec3& p, const Segment3& s) {
  const Vec3 d = s.b - s.a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (s.a + t * d)).norm();
}

}  // namespace

std::vector<double> pair_end_support(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                     const PairSupportOptions& support, double end_length_m, int threads) {
  // Each junction's nearby segments only, prepared relative to it: a query then tests tens of segments, not
  // the whole map, and finding them looks only at the segments whose x range can reach the junction.
  const SegmentsByX by_x(segments);
  const double reach = end_length_m + support.radius_m;
  auto near_of = [&](const Vec3& at) {
    std::vector<Segment3> close;
    const auto [first, last] = by_x.meeting(at.x() - reach, at.x() + reach);
    for (size_t k = first; k < last; ++k)
      if (point_segment_distance(at, by_x.segments()[k]) <= reach) close.push_back(by_x.segments()[k]);
    return AnchoredSegmentSupport(close, at);
  };
  // A junction index stands for the position it first comes with (a pair without one is prepared alone).
  std::vector<const Vec3*> where;
  for (const JunctionPair& p : pairs)
    for (const auto& [index, at] : {std::pair<int, const Vec3*>{p.i, &p.u}, {p.j, &p.v}})
      if (index >= 0) {
        if (where.size() <= static_cast<size_t>(index)) where.resize(static_cast<size_t>(index) + 1, nullptr);
        if (!where[static_cast<size_t>(index)]) where[static_cast<size_t>(index)] = at;
      }
  std::vector<std::optional<AnchoredSegmentSupport>> near(where.size());
  for_each_item(static_cast<int64_t>(where.size()), threads, [&](int64_t j) {
    if (where[static_cast<size_t>(j)]) near[static_cast<size_t>(j)].emplace(near_of(*where[static_cast<size_t>(j)]));
  }, 8);
  std::vector<double> rank(pairs.size());
  for_each_item(static_cast<int64_t>(pairs.size()), threads, [&](int64_t k) {
    const JunctionPair& p = pairs[static_cast<size_t>(k)];
    const double length = (p.v - p.u).norm();
    if (length < support.keep_shorter_than_m) {
      rank[static_cast<size_t>(k)] = 2.0;  // above any support share
      return;
    }
    const Vec3 d = (p.v - p.u) / length;
    const double reach = std::min(end_length_m, 0.5 * length);
    auto at_end = [&](int index, const Vec3& at, const Vec3& towards) {
      if (index >= 0) return near[static_cast<size_t>(index)]->support(towards, support.radius_m, support.max_angle_deg);
      return near_of(at).support(towards, support.radius_m, support.max_angle_deg);
    };
    rank[static_cast<size_t>(k)] = 0.5 * (at_end(p.i, p.u, p.u + reach * d) + at_end(p.j, p.v, p.v - reach * d));
  }, 256);
  return rank;
}

std::vector<JunctionPair> capped_pairs(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                       const PairCapOptions& cap, const PairSupportOptions& support, int threads) {
  cap.Check();
  support.Check();
  if (!cap.enabled() || pairs.size() <= static_cast<size_t>(cap.max_pairs)) return pairs;
  const std::vector<double> rank = pair_end_support(pairs, segments, support, cap.end_length_m, threads);
  std::vector<double> length2(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) length2[k] = (pairs[k].v - pairs[k].u).squaredNorm();
  std::vector<size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (rank[a] != rank[b]) return rank[a] > rank[b];
    return length2[a] < length2[b];
  });
  std::map<int, int> used;  // pairs kept per junction index
  std::vector<char> keep(pairs.size(), 0);
  size_t kept = 0;
  for (size_t k : order) {
    if (kept == static_cast<size_t>(cap.max_pairs)) break;
    const JunctionPair& p = pairs[k];
    if (cap.max_pairs_per_junction > 0 &&
        ((p.i >= 0 && used[p.i] >= cap.max_pairs_per_junction) || (p.j >= 0 && used[p.j] >= cap.max_pairs_per_junction)))
      continue;
    keep[k] = 1, ++kept;
    if (p.i >= 0) ++used[p.i];
    if (p.j >= 0) ++used[p.j];
  }
  std::vector<JunctionPair> out;
  out.reserve(kept);
  for (size_t k = 0; k < pairs.size(); ++k)
    if (keep[k]) out.push_back(pairs[k]);
  return out;
}

}  // namespace lc2wf
