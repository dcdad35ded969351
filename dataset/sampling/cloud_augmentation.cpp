#include "dataset/sampling/cloud_augmentation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dataset/formats/errors.h"
#include "dataset/sampling/rng.h"
#include "dataset/geometry/segment_split.h"

namespace lc2wf {
namespace {

// A segment on its way through the augmentation, with what its label needs at the end.
struct Piece {
  Segment3 s;
  SegmentLabel label;   // the source segment's label (for f = 1 only the edge matters)
  bool keeps_a = true;  // s.a is still the source's endpoint a (one-sided labels stay only there)
  bool keeps_b = true;
};

constexpr uint64_t kClutterStream = 0xC1u;
constexpr uint64_t kMergedMapStream = 0xC2u;

bool probability_ok(double p) { return p >= 0.0 && p <= 1.0; }

std::pair<int, int> edge_key(const SegmentLabel& l) { return {std::min(l.i1, l.i2), std::max(l.i1, l.i2)}; }

// One line through the longest fragment, spanning every fragment's endpoints projected onto it.
Segment3 fuse(const std::vector<const Piece*>& group) {
  const Piece* longest = *std::max_element(group.begin(), group.end(),
                                           [](const Piece* x, const Piece* y) { return x->s.length() < y->s.length(); });
  const Vec3 origin = longest->s.a;
  const Vec3 dir = (longest->s.b - longest->s.a).normalized();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Piece* p : group)
    for (const Vec3& e : {p->s.a, p->s.b}) {
      const double t = dir.dot(e - origin);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
  return {origin + lo * dir, origin + hi * dir};
}

std::vector<Piece> merge_edge_fragments(std::vector<Piece> pieces, double prob, DataRng& rng) {
  std::map<std::pair<int, int>, std::vector<size_t>> by_edge;  // ordered: the draws do not depend on hashing
  for (size_t i = 0; i < pieces.size(); ++i)
    if (pieces[i].label.f) by_edge[edge_key(pieces[i].label)].push_back(i);
  std::vector<int> fused_into(pieces.size(), -1);  // index of the group's first member, or -1
  std::vector<Segment3> fused(pieces.size());
  for (const auto& [edge, members] : by_edge) {
    if (members.size() < 2 || rng.uniform() >= prob) continue;
    std::vector<const Piece*> group;
    for (size_t i : members) group.push_back(&pieces[i]);
    fused[members.front()] = fuse(group);
    for (size_t i : members) fused_into[i] = static_cast<int>(members.front());
  }
  std::vector<Piece> out;
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (fused_into[i] < 0) {
      out.push_back(pieces[i]);
    } else if (fused_into[i] == static_cast<int>(i)) {
      Piece p = pieces[i];
      p.s = fused[i];
      p.keeps_a = p.keeps_b = false;
      out.push_back(p);
    }
  }
  return out;
}

// Two or three pieces along the segment, each cut shortened by a gap of up to 10 % of the length.
void split_piece(const Piece& p, double min_length, DataRng& rng, std::vector<Piece>& out) {
  const int count = 2 + static_cast<int>(rng.below(2));
  std::vector<double> cuts{0.0, 1.0};
  for (int c = 1; c < count; ++c) cuts.push_back(rng.uniform(0.15, 0.85));
  std::sort(cuts.begin(), cuts.end());
  const Vec3 d = p.s.b - p.s.a;
  const double length = d.norm();
  bool made = false;
  for (int k = 0; k < count; ++k) {
    const double t0 = cuts[k] + (k > 0 ? 0.5 * rng.uniform(0.0, 0.1) : 0.0);
    const double t1 = cuts[k + 1] - (k + 1 < count ? 0.5 * rng.uniform(0.0, 0.1) : 0.0);
    if ((t1 - t0) * length < min_length) continue;
    Piece q = p;
    q.s = {p.s.a + t0 * d, p.s.a + t1 * d};
    q.keeps_a = p.keeps_a && k == 0;
    q.keeps_b = p.keeps_b && k + 1 == count;
    out.push_back(q);
    made = true;
  }
  if (!made) out.push_back(p);
}

// Own generator: without clutter every other draw stays what it was before clutter existed.
void append_clutter(const LineCloud& cloud, const CloudAugmentOptions& o, uint64_t seed, std::vector<Piece>& pieces) {
  if (o.face_clutter_max <= 0.0 && o.ground_clutter_max <= 0.0) return;
  DataRng rng(mix_seed(seed, kClutterStream));
  const double n = static_cast<double>(cloud.segments.size());
  SurfaceClutterOptions c;
  c.face_lines = static_cast<int>(std::lround(n * rng.uniform(0.0, o.face_clutter_max)));
  c.ground_lines = static_cast<int>(std::lround(n * rng.uniform(0.0, o.ground_clutter_max)));
  c.min_length_m = o.min_length_m;
  c.max_length_m = o.clutter_length_max_m;
  for (const Segment3& s : make_surface_clutter(cloud.wireframe, c, rng)) pieces.push_back({s, SegmentLabel{}, false, false});
}

// The staggered pieces inference cuts a merged line map into; a piece keeps a one-sided label's endpoint
// only where it still ends there.
std::vector<Piece> cut_as_merged_map(const std::vector<Piece>& pieces) {
  std::vector<Piece> out;
  std::vector<Segment3> cut;
  for (const Piece& p : pieces) {
    cut.clear();
    append_staggered_pieces(p.s, kMergedMapPieceLength, cut);
    for (const Segment3& s : cut) {
      Piece q = p;
      q.s = s;
      q.keeps_a = p.keeps_a && s.a == p.s.a;
      q.keeps_b = p.keeps_b && s.b == p.s.b;
      out.push_back(q);
    }
  }
  return out;
}

SegmentLabel relabel(const Piece& p, const Wireframe& wf) {
  if (p.label.f) return make_edge_label(p.s, wf, p.label.i1, p.label.i2);
  SegmentLabel l;
  if (p.keeps_a && p.label.i1 >= 0) {
    l.i1 = p.label.i1;
    l.d1 = (p.s.a - wf.junctions[l.i1]).norm();
  }
  if (p.keeps_b && p.label.i2 >= 0) {
    l.i2 = p.label.i2;
    l.d2 = (p.s.b - wf.junctions[l.i2]).norm();
  }
  return l;
}

}  // namespace

void CloudAugmentOptions::Check() const {
  if (!probability_ok(merge_prob_max)) throw std::invalid_argument("cloud_augment.merge_prob_max must be in [0, 1]");
  if (!probability_ok(split_prob_max)) throw std::invalid_argument("cloud_augment.split_prob_max must be in [0, 1]");
  if (!probability_ok(densify_prob_max)) throw std::invalid_argument("cloud_augment.densify_prob_max must be in [0, 1]");
  if (!(drop_max >= 0.0 && drop_max < 1.0)) throw std::invalid_argument("cloud_augment.drop_max must be in [0, 1)");
  if (!(endpoint_noise_max_m >= 0.0 && endpoint_noise_max_m <= 1.0))
    throw std::invalid_argument("cloud_augment.endpoint_noise_max_m must be in [0, 1] (metres)");
  if (!(min_length_m > 0.0 && min_length_m <= 10.0))
    throw std::invalid_argument("cloud_augment.min_length_m must be in (0, 10] (metres)");
  if (!(face_clutter_max >= 0.0 && face_clutter_max <= 20.0))
    throw std::invalid_argument("cloud_augment.face_clutter_max must be in [0, 20] (lines per segment of the cloud)");
  if (!(ground_clutter_max >= 0.0 && ground_clutter_max <= 20.0))
    throw std::invalid_argument("cloud_augment.ground_clutter_max must be in [0, 20] (lines per segment of the cloud)");
  if (!(clutter_length_max_m >= min_length_m && clutter_length_max_m <= 100.0))
    throw std::invalid_argument("cloud_augment.clutter_length_max_m must be in [min_length_m, 100] (metres)");
  if (!probability_ok(merged_map_prob)) throw std::invalid_argument("cloud_augment.merged_map_prob must be in [0, 1]");
}

LineCloud augment_cloud_statistics(const LineCloud& cloud, const CloudAugmentOptions& o, uint64_t seed) {
  o.Check();
  if (cloud.segments.empty()) throw DataError(cloud.name.empty() ? "line cloud" : cloud.name, "empty line cloud (no segments)");
  const bool labelled = cloud.labels.size() == cloud.segments.size();
  DataRng rng(seed);
  const double merge_p = rng.uniform(0.0, o.merge_prob_max);
  const double split_p = rng.uniform(0.0, o.split_prob_max);
  const double densify_p = rng.uniform(0.0, o.densify_prob_max);
  const double drop_p = rng.uniform(0.0, o.drop_max);
  const double sigma = rng.uniform(0.0, o.endpoint_noise_max_m);
  // Own generator: with merged_map_prob 0 every other draw stays what it was before the key existed.
  const bool merged_map = o.merged_map_prob > 0.0 && DataRng(mix_seed(seed, kMergedMapStream)).uniform() < o.merged_map_prob;

  std::vector<Piece> pieces;
  pieces.reserve(cloud.segments.size());
  for (size_t i = 0; i < cloud.segments.size(); ++i)
    pieces.push_back({cloud.segments[i], labelled ? cloud.labels[i] : SegmentLabel{}});
  if (labelled) pieces = merge_edge_fragments(std::move(pieces), merged_map ? 1.0 : merge_p, rng);

  std::vector<Piece> reshaped;
  for (const Piece& p : pieces) {
    if (rng.uniform() < split_p) split_piece(p, o.min_length_m, rng, reshaped);
    else reshaped.push_back(p);
    if (rng.uniform() < densify_p) reshaped.push_back(reshaped.back());
  }
  append_clutter(cloud, o, seed, reshaped);

  std::vector<Piece> kept;
  for (const Piece& p : reshaped) {
    if (rng.uniform() < drop_p) continue;
    Piece q = p;
    q.s.a += sigma * Vec3(rng.normal(), rng.normal(), rng.normal());
    q.s.b += sigma * Vec3(rng.normal(), rng.normal(), rng.normal());
    if (q.s.length() < o.min_length_m) q.s = p.s;  // noise must not collapse a segment
    kept.push_back(q);
  }
  if (kept.empty()) kept.push_back(reshaped.front());  // every line dropped: keep the first, a cloud needs one
  if (merged_map) kept = cut_as_merged_map(kept);

  LineCloud out;
  out.name = cloud.name;
  out.cameras = cloud.cameras;
  out.wireframe = cloud.wireframe;
  out.units = cloud.units;
  for (const Piece& q : kept) {
    out.segments.push_back(q.s);
    if (labelled) out.labels.push_back(relabel(q, cloud.wireframe));
  }
  return out;
}

}  // namespace lc2wf
