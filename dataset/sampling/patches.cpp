#include "dataset/sampling/patches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

constexpr double kFar = 1e5;  // release: zero-length segments sit at distance 100000

// Writes [near - c, far - c] / scale (6 floats) for segment s seen from c.
void write_endpoints(const Segment3& s, const Vec3& c, double inv_scale, float* out) {
  const bool a_near = (s.a - c).squaredNorm() <= (s.b - c).squaredNorm();
  const Vec3 n = ((a_near ? s.a : s.b) - c) * inv_scale;
  const Vec3 f = ((a_near ? s.b : s.a) - c) * inv_scale;
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<float>(n[k]);
    out[3 + k] = static_cast<float>(f[k]);
  }
}

}  // namespace

void PatchOptions::Check() const {
  if (lines_per_patch < 1) throw std::invalid_argument("PatchOptions.lines_per_patch must be >= 1");
  if (!(radius_m > 0)) throw std::invalid_argument("PatchOptions.radius_m must be > 0");
  if (!(positive_radius_m > 0)) throw std::invalid_argument("PatchOptions.positive_radius_m must be > 0");
  if (negative_noise_count < 1 || negative_noise_count > lines_per_patch) {
    throw std::invalid_argument("PatchOptions.negative_noise_count must be in [1, lines_per_patch]");
  }
  frame.Check();
}

SegmentSet::SegmentSet(const std::vector<Segment3>& segments) : segments_(segments) {
  const size_t n = segments.size();
  for (auto* v : {&ax_, &ay_, &az_, &dx_, &dy_, &dz_, &inv_len_, &inv_len2_, &far_}) v->resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = segments[i].b - segments[i].a;
    ax_[i] = segments[i].a.x();
    ay_[i] = segments[i].a.y();
    az_[i] = segments[i].a.z();
    dx_[i] = d.x();
    dy_[i] = d.y();
    dz_[i] = d.z();
    const double len = d.norm();
    inv_len_[i] = len > 0 ? 1.0 / (len + 1e-6) : 0.0;
    inv_len2_[i] = len > 0 ? 1.0 / (len * len) : 0.0;
    far_[i] = len > 0 ? 0.0 : kFar * kFar;
  }
}

namespace {

// The k smallest of d2[0..n) (ties: lower index) in ascending order, as square roots.
void smallest_k(const double* d2, size_t n, int k, std::vector<int>& idx, std::vector<double>& dist) {
  // Running top-k by insertion: after the first few hundred segments insertions become rare.
  const size_t m = std::min<size_t>(static_cast<size_t>(std::max(k, 0)), n);
  idx.clear();
  dist.clear();
  if (m == 0) return;
  for (size_t i = 0; i < n; ++i) {
    const double di = d2[i];
    if (idx.size() == m && di >= dist.back()) continue;  // ties keep the lower index (already in)
    size_t pos = idx.size() < m ? idx.size() : m - 1;
    if (idx.size() < m) {
      idx.push_back(0);
      dist.push_back(0);
    }
    while (pos > 0 && dist[pos - 1] > di) {
      idx[pos] = idx[pos - 1];
      dist[pos] = dist[pos - 1];
      --pos;
    }
    idx[pos] = static_cast<int>(i);
    dist[pos] = di;
  }
  for (auto& v : dist) v = std::sqrt(v);
}

}  // namespace

PatchDistance parse_patch_distance(const std::string& name, const std::string& where) {
  if (name == "infinite_line") return PatchDistance::InfiniteLine;
  if (name == "segment") return PatchDistance::Segment;
  throw std::invalid_argument(where + ": '" + name + "' is not a patch distance (infinite_line or segment)");
}

const char* patch_distance_name(PatchDistance d) { return d == PatchDistance::Segment ? "segment" : "infinite_line"; }

void SegmentSet::nearest(const Vec3& q, int k, PatchDistance distance, std::vector<int>& idx, std::vector<double>& dist) const {
  const size_t n = segments_.size();
  const double qx = q.x(), qy = q.y(), qz = q.z();
  thread_local std::vector<double> scratch;  // per-thread, so concurrent queries on one set are safe
  scratch.resize(n);
  double* d2 = scratch.data();
  if (distance == PatchDistance::InfiniteLine) {
    // Squared |AB x (q - A)| / (|AB| + 1e-6): same order as the release's distance, no sqrt, vectorisable.
    for (size_t i = 0; i < n; ++i) {
      const double px = qx - ax_[i], py = qy - ay_[i], pz = qz - az_[i];
      const double cx = dy_[i] * pz - dz_[i] * py;
      const double cy = dz_[i] * px - dx_[i] * pz;
      const double cz = dx_[i] * py - dy_[i] * px;
      d2[i] = (cx * cx + cy * cy + cz * cz) * (inv_len_[i] * inv_len_[i]) + far_[i];
    }
  } else {
    for (size_t i = 0; i < n; ++i) {
      const double px = qx - ax_[i], py = qy - ay_[i], pz = qz - az_[i];
      const double t = std::clamp((px * dx_[i] + py * dy_[i] + pz * dz_[i]) * inv_len2_[i], 0.0, 1.0);
      const double ex = px - t * dx_[i], ey = py - t * dy_[i], ez = pz - t * dz_[i];
      d2[i] = ex * ex + ey * ey + ez * ez + far_[i];
    }
  }
  smallest_k(d2, n, k, idx, dist);
}

double SegmentSet::segment_distance(size_t i, const Vec3& q) const {
  const Segment3& s = segments_[i];
  const Vec3 ab = s.b - s.a;
  const double len = ab.norm();
  if (len == 0) return (q - s.a).norm();
  const Vec3 u = ab / (len + 1e-8);
  const double h = std::max({(s.a - q).dot(u), (q - s.b).dot(u), 0.0});
  const double c = u.cross(q - s.a).norm();
  return std::sqrt(c * c + h * h);
}

JunctionPatches build_junction_patches(const SegmentSet& segs, const std::vector<int>& endpoint_labels,
                                       const std::vector<Vec3>& gt, const std::vector<int>& samples,
                                       const PatchOptions& o) {
  o.Check();
  const int n = static_cast<int>(segs.size());
  if (n == 0) throw std::invalid_argument("build_junction_patches: empty line cloud");
  if (!endpoint_labels.empty() && endpoint_labels.size() != 2 * segs.size()) {
    throw std::invalid_argument("build_junction_patches: endpoint_labels must have 2 per segment");
  }
  const int G = static_cast<int>(samples.size()), L = o.lines_per_patch;
  JunctionPatches P;
  P.num_patches = G;
  P.lines = L;
  P.features.assign(static_cast<size_t>(G) * L * JunctionPatches::kFeatures, 0.0f);
  P.padded.assign(static_cast<size_t>(G) * L, 1);
  P.points.assign(static_cast<size_t>(G) * 3, 0.0f);
  P.label.assign(G, -1);
  P.offset.assign(static_cast<size_t>(G) * 3, 0.0f);
  P.endpoint.assign(samples.begin(), samples.end());
  const double inv = 1.0 / o.frame.scale_m;
  auto label_of = [&](int seg, const Vec3& x) {
    if (endpoint_labels.empty()) return -1;
    const Segment3& s = segs.segment(seg);
    return (s.a - x).squaredNorm() <= (s.b - x).squaredNorm() ? endpoint_labels[2 * seg] : endpoint_labels[2 * seg + 1];
  };
  std::vector<int> idx, line_labels;
  std::vector<double> dist;
  std::map<int, int> hist;
  for (int g = 0; g < G; ++g) {
    const int e = samples[g];
    if (e < 0 || e >= 2 * n) throw std::out_of_range("build_junction_patches: sample endpoint out of range");
    const Vec3 x = (e % 2 == 0) ? segs.segment(e / 2).a : segs.segment(e / 2).b;
    const Vec3 xn = o.frame.to_network(x);
    for (int k = 0; k < 3; ++k) P.points[3 * g + k] = static_cast<float>(xn[k]);
    segs.nearest(x, L, o.distance, idx, dist);
    int padded = 0;
    line_labels.clear();
    for (int s = 0; s < L; ++s) {
      float* f = &P.features[(static_cast<size_t>(g) * L + s) * JunctionPatches::kFeatures];
      const bool valid = s < static_cast<int>(idx.size()) && dist[s] <= o.radius_m;
      P.padded[static_cast<size_t>(g) * L + s] = valid ? 0 : 1;
      padded += !valid;
      const int seg = valid ? idx[s] : 0;
      line_labels.push_back(label_of(seg, x));
      if (!valid && o.padding == PaddingMode::Zero) continue;
      write_endpoints(segs.segment(seg), x, inv, f);
      const int dist_seg = s < static_cast<int>(idx.size()) ? idx[s] : 0;
      f[6] = static_cast<float>(segs.segment_distance(dist_seg, x) * inv);
    }
    // Negative when at least half the slots are padding or at least `negative_noise_count` lines are noise.
    int label = -1;
    if (2 * padded < L) {
      hist.clear();
      int noise = 0;
      for (int l : line_labels) (l < 0 ? noise : hist[l]) += 1;
      if (noise < o.negative_noise_count) {
        int best = 0;
        for (const auto& [id, c] : hist) {
          if (c > best) {
            best = c;
            label = id;
          }
        }
      }
    }
    if (label >= static_cast<int>(gt.size())) {
      throw std::out_of_range("build_junction_patches: label " + std::to_string(label) + " but only " +
                              std::to_string(gt.size()) + " GT junctions");
    }
    if (label >= 0 && (gt[label] - x).norm() > o.positive_radius_m) label = -1;
    P.label[g] = label;
    if (label >= 0) {
      const Vec3 off = (gt[label] - x) * inv;
      for (int k = 0; k < 3; ++k) P.offset[3 * g + k] = static_cast<float>(off[k]);
    }
  }
  return P;
}

PairPatches build_pair_patches(const SegmentSet& segs, const std::vector<JunctionPair>& pairs, const PatchOptions& o) {
  o.Check();
  if (segs.size() == 0) throw std::invalid_argument("build_pair_patches: empty line cloud");
  const int P = static_cast<int>(pairs.size()), L = o.lines_per_patch, L2 = 2 * L;
  PairPatches out;
  out.num_pairs = P;
  out.lines = L2;
  out.features.assign(static_cast<size_t>(P) * L2 * PairPatches::kFeatures, 0.0f);
  out.padded.assign(static_cast<size_t>(P) * L2, 1);
  out.label.resize(P);
  const double inv = 1.0 / o.frame.scale_m;
  // Pairs share their junctions (512 pairs over ~100 points): query each distinct point once.
  std::map<std::array<double, 3>, std::pair<std::vector<int>, std::vector<double>>> cache;
  auto nearest = [&](const Vec3& q) -> const std::pair<std::vector<int>, std::vector<double>>& {
    auto [it, fresh] = cache.try_emplace({q.x(), q.y(), q.z()});
    if (fresh) segs.nearest(q, L, PatchDistance::InfiniteLine, it->second.first, it->second.second);  // the release's, for pairs
    return it->second;
  };
  for (int p = 0; p < P; ++p) {
    const auto& pr = pairs[p];
    out.label[p] = pr.label;
    const Vec3 m = 0.5 * (pr.u + pr.v);
    for (int side = 0; side < 2; ++side) {
      const auto& [idx, dist] = nearest(side == 0 ? pr.u : pr.v);
      for (int s = 0; s < L; ++s) {
        const size_t slot = static_cast<size_t>(p) * L2 + side * L + s;
        const bool valid = s < static_cast<int>(idx.size()) && dist[s] <= o.radius_m;
        out.padded[slot] = valid ? 0 : 1;
        if (!valid && o.padding == PaddingMode::Zero) continue;
        write_endpoints(segs.segment(valid ? idx[s] : 0), m, inv, &out.features[slot * PairPatches::kFeatures]);
      }
    }
  }
  return out;
}

namespace {

template <typename T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

}  // namespace

JunctionPatches stack(const std::vector<JunctionPatches>& parts) {
  JunctionPatches out;
  out.batch = 0;
  for (const auto& p : parts) {
    if (out.batch > 0 && (p.num_patches != out.num_patches || p.lines != out.lines)) {
      throw std::invalid_argument("stack: junction patches differ in G or L");
    }
    out.num_patches = p.num_patches;
    out.lines = p.lines;
    out.batch += p.batch;
    append(out.features, p.features);
    append(out.padded, p.padded);
    append(out.points, p.points);
    append(out.label, p.label);
    append(out.offset, p.offset);
    append(out.endpoint, p.endpoint);
  }
  return out;
}

PairPatches stack(const std::vector<PairPatches>& parts) {
  PairPatches out;
  out.batch = 0;
  for (const auto& p : parts) {
    if (out.batch > 0 && (p.num_pairs != out.num_pairs || p.lines != out.lines)) {
      throw std::invalid_argument("stack: pair patches differ in P or L");
    }
    out.num_pairs = p.num_pairs;
    out.lines = p.lines;
    out.batch += p.batch;
    append(out.features, p.features);
    append(out.padded, p.padded);
    append(out.label, p.label);
  }
  return out;
}

namespace {

// Rows [first, first + count) of a batch whose buildings each hold size / batch values.
template <class T>
std::vector<T> rows(const std::vector<T>& v, int batch, int first, int count) {
  const size_t per = v.size() / static_cast<size_t>(batch);
  return std::vector<T>(v.begin() + static_cast<std::ptrdiff_t>(per * first),
                        v.begin() + static_cast<std::ptrdiff_t>(per * (first + count)));
}

void check_slice(int batch, int first, int count) {
  if (first < 0 || count < 1 || first + count > batch)
    throw std::invalid_argument("slice: buildings [" + std::to_string(first) + ", " + std::to_string(first + count) +
                                ") outside a batch of " + std::to_string(batch));
}

}  // namespace

JunctionPatches slice(const JunctionPatches& b, int first, int count) {
  check_slice(b.batch, first, count);
  JunctionPatches out;
  out.batch = count;
  out.num_patches = b.num_patches;
  out.lines = b.lines;
  out.features = rows(b.features, b.batch, first, count);
  out.padded = rows(b.padded, b.batch, first, count);
  out.points = rows(b.points, b.batch, first, count);
  out.label = rows(b.label, b.batch, first, count);
  out.offset = rows(b.offset, b.batch, first, count);
  out.endpoint = rows(b.endpoint, b.batch, first, count);
  return out;
}

PairPatches slice(const PairPatches& b, int first, int count) {
  check_slice(b.batch, first, count);
  PairPatches out;
  out.batch = count;
  out.num_pairs = b.num_pairs;
  out.lines = b.lines;
  out.features = rows(b.features, b.batch, first, count);
  out.padded = rows(b.padded, b.batch, first, count);
  out.label = rows(b.label, b.batch, first, count);
  return out;
}

}  // namespace lc2wf
