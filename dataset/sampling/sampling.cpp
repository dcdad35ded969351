#include "dataset/sampling/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/util/quantile.h"
#include "dataset/selection/point_nms.h"
#include "dataset/sampling/rng.h"
#include "dataset/geometry/spatial_grid.h"

namespace lc2wf {

void DensitySeedRule::Check() const {
  if (min_count < 0 || min_count > 1000) throw std::invalid_argument("DensitySeedRule.min_count must be in [0, 1000]");
  if (!(min_ratio >= 0 && min_ratio <= 1)) throw std::invalid_argument("DensitySeedRule.min_ratio must be in [0, 1]");
  if (!(nms_m >= 0 && nms_m <= 10)) throw std::invalid_argument("DensitySeedRule.nms_m must be in [0, 10] (metres)");
}

std::string DensitySeedRule::str() const {
  if (*this == release()) return "release";
  if (*this == loose()) return "loose";
  char text[96];
  std::snprintf(text, sizeof text, "%d,%g,%g", min_count, min_ratio, nms_m);
  return text;
}

DensitySeedRule DensitySeedRule::parse(const std::string& text) {
  if (text == "release") return release();
  if (text == "loose") return loose();
  DensitySeedRule r;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%d,%lf,%lf%c", &r.min_count, &r.min_ratio, &r.nms_m, &rest) != 3) {
    throw std::invalid_argument("'" + text + "' is not release, loose or MIN_COUNT,MIN_RATIO,NMS_M (e.g. 4,0.5,0.3)");
  }
  r.Check();
  return r;
}

void SamplingOptions::Check() const {
  if (num_samples < 1) throw std::invalid_argument("SamplingOptions.num_samples must be >= 1");
  if (!(density_radius_m > 0)) throw std::invalid_argument("SamplingOptions.density_radius_m must be > 0");
  if (!(density_inner_radius_m > 0 && density_inner_radius_m <= density_radius_m)) {
    throw std::invalid_argument("SamplingOptions.density_inner_radius_m must be in (0, density_radius_m]");
  }
  seeds.Check();
  if (near_gt_samples < 0) throw std::invalid_argument("SamplingOptions.near_gt_samples must be >= 0");
  if (!(near_gt_radius_m > 0)) throw std::invalid_argument("SamplingOptions.near_gt_radius_m must be > 0");
  if (passes < 1 || passes > 8) throw std::invalid_argument("SamplingOptions.passes must be in [1, 8]");
}

std::vector<Vec3> segment_endpoints(const std::vector<Segment3>& segments) {
  std::vector<Vec3> out;
  out.reserve(2 * segments.size());
  for (const auto& s : segments) {
    out.push_back(s.a);
    out.push_back(s.b);
  }
  return out;
}

std::vector<int> density_seeds(const std::vector<Vec3>& p, const SamplingOptions& o) {
  o.Check();
  if (p.empty()) return {};
  const SpatialGrid grid(p, o.density_radius_m);
  std::vector<int> cand, count(p.size(), 0);
  std::vector<double> ratio(p.size(), 0.0);
  for (size_t i = 0; i < p.size(); ++i) {
    int b = 0;
    grid.count_within(p[i], o.density_radius_m, o.density_inner_radius_m, count[i], b);
    ratio[i] = b / (count[i] + 1e-3);
    if (count[i] > o.seeds.min_count && ratio[i] > o.seeds.min_ratio) cand.push_back(static_cast<int>(i));
  }
  std::vector<Vec3> cp;
  std::vector<double> cs;
  for (int i : cand) {
    cp.push_back(p[i]);
    cs.push_back(ratio[i]);
  }
  std::vector<int> out;
  for (int k : point_nms(cp, cs, o.seeds.nms_m, PointNmsRule::kSuppressor)) out.push_back(cand[k]);
  // A building's corners end a fragment in nearly every view that sees them; window frames, leaves and other
  // clutter in fewer: when a cluttered cloud has more seeds than sample points, the most endpoints go first.
  std::stable_sort(out.begin(), out.end(), [&](int a, int b) { return count[a] > count[b]; });
  return out;
}

int passes_for_extent(const std::vector<Segment3>& segments, double metres_per_pass, int max_passes) {
  if (!(metres_per_pass > 0) || segments.empty()) return 1;
  double extent = 0;
  for (int axis : {0, 1}) {
    std::vector<double> v;
    v.reserve(2 * segments.size());
    for (const Segment3& s : segments) v.push_back(s.a[axis]), v.push_back(s.b[axis]);
    extent = std::max(extent, quantile(v, 0.98) - quantile(v, 0.02));
  }
  const double passes = std::ceil(extent / metres_per_pass);
  return static_cast<int>(std::clamp(passes, 1.0, static_cast<double>(std::max(1, max_passes))));
}

std::vector<int> farthest_point_sampling(const std::vector<Vec3>& p, int count, const std::vector<int>& seeds) {
  const int n = static_cast<int>(p.size());
  std::vector<int> out;
  if (n == 0 || count <= 0) return out;
  if (n <= count) {
    for (int k = 0; k < count; ++k) out.push_back(k % n);
    return out;
  }
  std::vector<char> taken(n, 0);
  for (int s : seeds) {
    if (s < 0 || s >= n) throw std::out_of_range("farthest_point_sampling: seed index out of range");
    if (!taken[s] && static_cast<int>(out.size()) < count) {
      taken[s] = 1;
      out.push_back(s);
    }
  }
  if (out.empty()) {
    out.push_back(0);
    taken[0] = 1;
  }
  // Structure-of-arrays so the update loop vectorises.
  std::vector<double> xs(n), ys(n), zs(n), dist(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    xs[i] = p[i].x();
    ys[i] = p[i].y();
    zs[i] = p[i].z();
  }
  auto relax = [&](int s) {
    const double sx = xs[s], sy = ys[s], sz = zs[s];
    for (int i = 0; i < n; ++i) {
      const double dx = xs[i] - sx, dy = ys[i] - sy, dz = zs[i] - sz;
      dist[i] = std::min(dist[i], dx * dx + dy * dy + dz * dz);
    }
  };
  for (int s : out) relax(s);
  while (static_cast<int>(out.size()) < count) {
    const int best = static_cast<int>(std::max_element(dist.begin(), dist.end()) - dist.begin());  // first on ties
    out.push_back(best);
    relax(best);
  }
  return out;
}

namespace {

// `first` followed by more points up to `count`: farthest-point sampling goes on from them when there are
// enough endpoints; otherwise the endpoints not yet taken come next, then the list repeats.
std::vector<int> continue_sampling(const std::vector<Vec3>& endpoints, std::vector<int> first, int count) {
  const int n = static_cast<int>(endpoints.size());
  if (first.empty()) return first;
  if (n > count) return farthest_point_sampling(endpoints, count, first);  // seeds keep their order
  std::vector<char> taken(static_cast<size_t>(n), 0);
  for (int s : first) taken[static_cast<size_t>(s)] = 1;
  for (int i = 0; i < n; ++i)
    if (!taken[static_cast<size_t>(i)]) first.push_back(i);
  const size_t distinct = first.size();
  while (static_cast<int>(first.size()) < count) first.push_back(first[first.size() % distinct]);
  first.resize(static_cast<size_t>(count));
  return first;
}

}  // namespace

std::vector<int> sample_endpoints(const std::vector<Vec3>& endpoints, const SamplingOptions& o,
                                  const std::vector<Vec3>* gt, DataRng* rng) {
  o.Check();
  std::vector<int> seeds;
  if (o.near_gt_samples > 0) {
    if (!gt || !rng) throw std::invalid_argument("sample_endpoints: near_gt_samples needs GT junctions and a generator");
    const double r2 = o.near_gt_radius_m * o.near_gt_radius_m;
    std::vector<int> near;
    for (size_t i = 0; i < endpoints.size(); ++i) {
      for (const auto& j : *gt) {
        if ((endpoints[i] - j).squaredNorm() <= r2) {
          near.push_back(static_cast<int>(i));
          break;
        }
      }
    }
    rng->shuffle(near);
    if (static_cast<int>(near.size()) > o.near_gt_samples) near.resize(o.near_gt_samples);
    seeds = std::move(near);
  }
  const auto dens = density_seeds(endpoints, o);
  seeds.insert(seeds.end(), dens.begin(), dens.end());
  std::vector<int> first = farthest_point_sampling(endpoints, o.num_samples, seeds);
  if (o.passes == 1) return first;
  // The seeds one pass could not hold lead the next passes, before farthest-point sampling goes on.
  std::vector<char> taken(endpoints.size(), 0);
  for (int s : first) taken[static_cast<size_t>(s)] = 1;
  for (int s : seeds)
    if (!taken[static_cast<size_t>(s)]) taken[static_cast<size_t>(s)] = 1, first.push_back(s);
  return continue_sampling(endpoints, std::move(first), o.passes * o.num_samples);
}

}  // namespace lc2wf
