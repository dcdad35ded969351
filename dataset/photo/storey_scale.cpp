#include "dataset/photo/storey_scale.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/util/quantile.h"

namespace lc2wf {

void StoreyScaleOptions::Check() const {
  if (!(storey_height_m >= 0 && storey_height_m <= 20)) throw std::invalid_argument("StoreyScaleOptions.storey_height_m must be in [0, 20]");
  if (!(storey_uncertainty >= 0 && storey_uncertainty < 1)) throw std::invalid_argument("StoreyScaleOptions.storey_uncertainty must be in [0, 1)");
  if (!(vertical_max_deg > 0 && vertical_max_deg < 45)) throw std::invalid_argument("StoreyScaleOptions.vertical_max_deg must be in (0, 45)");
  if (min_lines < 3) throw std::invalid_argument("StoreyScaleOptions.min_lines must be >= 3");
  if (min_repeats < 2 || max_storeys <= min_repeats || max_storeys > 200)
    throw std::invalid_argument("StoreyScaleOptions.min_repeats must be >= 2 and < max_storeys <= 200");
  if (!(bin_fraction >= 1e-4 && bin_fraction <= 0.01)) throw std::invalid_argument("StoreyScaleOptions.bin_fraction must be in [1e-4, 0.01]");
  if (!(smooth_fraction >= 0 && smooth_fraction <= 0.05)) throw std::invalid_argument("StoreyScaleOptions.smooth_fraction must be in [0, 0.05]");
  if (!(min_strength > 0 && min_strength < 1)) throw std::invalid_argument("StoreyScaleOptions.min_strength must be in (0, 1)");
  if (!(fundamental_share > 0 && fundamental_share <= 1)) throw std::invalid_argument("StoreyScaleOptions.fundamental_share must be in (0, 1]");
}

namespace {

std::vector<double> gaussian_smooth(const std::vector<double>& p, double sigma) {
  if (sigma <= 0) return p;
  const int n = static_cast<int>(p.size()), reach = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(2 * reach + 1), out(n, 0.0);
  double sum = 0;
  for (int k = -reach; k <= reach; ++k) sum += kernel[k + reach] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (int i = 0; i < n; ++i)
    for (int k = -reach; k <= reach; ++k)
      if (i + k >= 0 && i + k < n) out[i] += p[i + k] * kernel[k + reach] / sum;
  return out;
}

// Where many lines crowd (the ground floor of a busy street) must not outweigh the rhythm: the profile is
// capped at the 90th percentile of its non-zero bins.
void cap_crowds(std::vector<double>& p) {
  std::vector<double> nonzero;
  for (double v : p)
    if (v > 0) nonzero.push_back(v);
  if (nonzero.empty()) return;
  const double cap = quantile(std::move(nonzero), 0.9);
  for (double& v : p) v = std::min(v, cap);
}

// The profile minus its moving average over `window` bins: what is left is the rhythm, not where lines crowd.
std::vector<double> high_pass(const std::vector<double>& p, int window) {
  const int n = static_cast<int>(p.size()), half = std::max(1, window / 2);
  std::vector<double> prefix(n + 1, 0.0), out(n);
  for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + p[i];
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - half), b = std::min(n, i + half + 1);
    out[i] = p[i] - (prefix[b] - prefix[a]) / (b - a);
  }
  return out;
}

// Biased (divided by the energy at lag 0): long lags overlap less and score less, so one storey beats two.
std::vector<double> autocorrelation(const std::vector<double>& d, int max_lag) {
  double energy = 0;
  for (double v : d) energy += v * v;
  std::vector<double> r(max_lag + 2, 0.0);
  if (!(energy > 0)) return r;
  for (int lag = 0; lag <= max_lag + 1 && lag < static_cast<int>(d.size()); ++lag) {
    double s = 0;
    for (size_t i = 0; i + lag < d.size(); ++i) s += d[i] * d[i + lag];
    r[lag] = s / energy;
  }
  return r;
}

}  // namespace

StoreyScale estimate_storey_scale(const std::vector<Segment3>& segments, double height, const StoreyScaleOptions& o) {
  o.Check();
  StoreyScale s;
  if (o.storey_height_m == 0) return s.why_not = "turned off", s;
  if (!(height > 0 && std::isfinite(height))) return s.why_not = "the cloud has no height", s;
  const double bin = height * o.bin_fraction;
  const int bins = static_cast<int>(std::ceil(1.2 / o.bin_fraction));  // ground to a little above the top
  const double min_rise = std::cos(o.vertical_max_deg * M_PI / 180.0);
  std::vector<double> change(bins + 1, 0.0);  // coverage as +1 / -1 at each line's ends
  for (const Segment3& seg : segments) {
    const Vec3 d = seg.b - seg.a;
    const double len = d.norm();
    // Whole-wall corners and eaves-to-ground lines cover every storey alike: no rhythm in them.
    if (!(len > 0) || !std::isfinite(len) || std::abs(d.z()) < min_rise * len || std::abs(d.z()) >= 0.5 * height) continue;
    const auto to_bin = [&](double z) { return std::clamp(static_cast<int>(std::floor(z / bin)), 0, bins); };
    const int lo = to_bin(std::min(seg.a.z(), seg.b.z())), hi = to_bin(std::max(seg.a.z(), seg.b.z()));
    if (hi > lo) change[lo] += 1, change[hi] -= 1, ++s.vertical_lines;
  }
  if (s.vertical_lines < o.min_lines) return s.why_not = "too few short vertical lines", s;
  std::vector<double> coverage(bins, 0.0);
  for (int i = 0, c = 0; i < bins; ++i) coverage[i] = c += static_cast<int>(change[i]);
  std::vector<double> profile = gaussian_smooth(coverage, o.smooth_fraction / o.bin_fraction);
  cap_crowds(profile);
  const int min_lag = std::max(static_cast<int>(std::ceil(6 * o.smooth_fraction / o.bin_fraction)),
                               static_cast<int>(std::floor(1.0 / (o.max_storeys * o.bin_fraction))));
  const int max_lag = static_cast<int>(std::ceil(1.0 / (o.min_repeats * o.bin_fraction)));
  const std::vector<double> r = autocorrelation(high_pass(profile, static_cast<int>(1.0 / o.bin_fraction)), max_lag);

  std::vector<int> peaks;  // positive local maxima inside the range
  double best = 0;
  for (int lag = std::max(1, min_lag); lag <= max_lag; ++lag)
    if (r[lag] > 0 && r[lag] >= r[lag - 1] && r[lag] > r[lag + 1]) peaks.push_back(lag), best = std::max(best, r[lag]);
  if (peaks.empty() || best < o.min_strength) return s.strength = best, s.why_not = "no storey rhythm in the vertical lines", s;
  // 2 and 3 storeys repeat as well as one: from the best peak, step down to a peak at a half or a third of it
  // that repeats nearly as well.
  int lag = *std::max_element(peaks.begin(), peaks.end(), [&](int a, int b) { return r[a] < r[b]; });
  for (bool stepped = true; stepped;) {
    stepped = false;
    for (int k : {2, 3})
      for (int p : peaks)
        if (!stepped && std::abs(p * k - lag) <= 0.05 * lag && r[p] >= o.fundamental_share * r[lag]) lag = p, stepped = true;
  }
  s.found = true;
  s.period = lag * bin;
  s.strength = r[lag];
  s.storeys = height / s.period;
  s.metres_per_unit = o.storey_height_m / s.period;
  return s;
}

nlohmann::json storey_scale_json(const StoreyScale& s, const StoreyScaleOptions& o) {
  nlohmann::json j = {{"found", s.found}, {"vertical_lines", s.vertical_lines}, {"strength", s.strength},
                      {"storey_height_m", o.storey_height_m}};
  if (!s.found) return j["why_not"] = s.why_not, j;
  j["period_input_units"] = s.period;
  j["storeys"] = s.storeys;
  j["metres_per_unit"] = s.metres_per_unit;
  j["relative_uncertainty"] = o.storey_uncertainty;
  return j;
}

}  // namespace lc2wf
