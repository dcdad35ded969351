#include "dataset/synthetic/long_fragment_cloud.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "dataset/formats/errors.h"
#include "dataset/sampling/rng.h"

namespace lc2wf {

void LongFragmentOptions::Check() const {
  if (!(min_pieces >= 1 && max_pieces >= min_pieces && max_pieces <= 100))
    throw std::invalid_argument("LongFragmentOptions: need 1 <= min_pieces <= max_pieces <= 100");
  if (!(gap_fraction_max >= 0.0 && gap_fraction_max < 0.5)) throw std::invalid_argument("LongFragmentOptions.gap_fraction_max must be in [0, 0.5)");
  if (!(noise_m >= 0.0 && noise_m <= 1.0)) throw std::invalid_argument("LongFragmentOptions.noise_m must be in [0, 1] (metres)");
  if (!(clutter_keep >= 0.0 && clutter_keep <= 1.0)) throw std::invalid_argument("LongFragmentOptions.clutter_keep must be in [0, 1]");
  if (!(min_length_m > 0.0)) throw std::invalid_argument("LongFragmentOptions.min_length_m must be > 0");
}

LineCloud make_long_fragment_cloud(const LineCloud& in, const LongFragmentOptions& o, uint64_t seed) {
  o.Check();
  const std::string source = in.name.empty() ? "line cloud" : in.name;
  if (in.labels.size() != in.segments.size() || in.segments.empty()) throw DataError(source, "needs a labelled line cloud");
  if (in.wireframe.edges.empty()) throw DataError(source, "has no ground-truth edges to fragment");
  DataRng rng(seed);
  LineCloud out;
  out.name = in.name;
  out.cameras = in.cameras;
  out.wireframe = in.wireframe;
  out.units = in.units;
  // Explicit Vec3: an Eigen expression returned by value would refer to the destroyed temporary.
  auto jitter = [&](const Vec3& p) -> Vec3 { return p + o.noise_m * Vec3(rng.normal(), rng.normal(), rng.normal()); };
  for (const auto& [j, k] : in.wireframe.edges) {
    const Vec3 a = in.wireframe.junctions[j], d = in.wireframe.junctions[k] - a;
    const int pieces = o.min_pieces + static_cast<int>(rng.below(static_cast<uint64_t>(o.max_pieces - o.min_pieces + 1)));
    std::vector<double> cuts{0.0, 1.0};
    for (int c = 1; c < pieces; ++c) cuts.push_back(rng.uniform());
    std::sort(cuts.begin(), cuts.end());
    for (int p = 0; p < pieces; ++p) {
      const double t0 = cuts[p] + (p > 0 ? 0.5 * rng.uniform(0.0, o.gap_fraction_max) : 0.0);
      const double t1 = cuts[p + 1] - (p + 1 < pieces ? 0.5 * rng.uniform(0.0, o.gap_fraction_max) : 0.0);
      const Segment3 s{jitter(a + t0 * d), jitter(a + t1 * d)};
      if ((t1 - t0) * d.norm() < o.min_length_m || s.length() < o.min_length_m) continue;
      out.segments.push_back(s);
      out.labels.push_back(make_edge_label(s, in.wireframe, j, k));
    }
  }
  for (size_t i = 0; i < in.segments.size(); ++i) {
    if (in.labels[i].f || rng.uniform() >= o.clutter_keep) continue;
    out.segments.push_back(in.segments[i]);
    out.labels.push_back(in.labels[i]);
  }
  if (out.segments.empty()) throw DataError(source, "every GT edge is shorter than the minimum fragment length");
  return out;
}

}  // namespace lc2wf
