#include "dataset/photo/line_height.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/util/atomic_file.h"
#include "core/util/input_file.h"
#include "core/util/json_text.h"
#include "core/util/quantile.h"

namespace lc2wf {

namespace {

// |cos| of the angle to z: above this a line is near vertical, below the second near horizontal (10 deg each).
constexpr double kVerticalCos = 0.985, kHorizontalCos = 0.17;
constexpr double kLowestLog2 = -7.0, kBinLog2 = 0.5;

constexpr double kEndSlab = 0.15;  // share of the height that is a cloud's bottom or top end

double relative_error(double predicted_log, double true_log) { return std::abs(std::exp(predicted_log - true_log) - 1.0); }

// Mean and (population) standard deviation of each statistic over `rows`; a constant one gets 1, not 0.
void standardisation(const std::vector<const std::vector<double>*>& rows, std::vector<double>* mean, std::vector<double>* stddev) {
  mean->assign(kLineStatisticsSize, 0.0), stddev->assign(kLineStatisticsSize, 0.0);
  for (const auto* r : rows)
    for (int d = 0; d < kLineStatisticsSize; ++d) (*mean)[d] += (*r)[d] / static_cast<double>(rows.size());
  for (const auto* r : rows)
    for (int d = 0; d < kLineStatisticsSize; ++d) (*stddev)[d] += std::pow((*r)[d] - (*mean)[d], 2) / static_cast<double>(rows.size());
  for (double& v : *stddev) v = v > 1e-18 ? std::sqrt(v) : 1.0;
}

// The k clouds nearest `z` (standardised) as (squared distance, index), nearest first; ties go to the earlier cloud.
std::vector<std::pair<double, size_t>> nearest(const std::vector<std::vector<double>>& clouds, const std::vector<double>& z, int k) {
  std::vector<std::pair<double, size_t>> d(clouds.size());
  for (size_t i = 0; i < clouds.size(); ++i) {
    double sum = 0;
    for (int c = 0; c < kLineStatisticsSize; ++c) sum += (clouds[i][c] - z[c]) * (clouds[i][c] - z[c]);
    d[i] = {sum, i};
  }
  const size_t kk = std::min(clouds.size(), static_cast<size_t>(k));
  std::partial_sort(d.begin(), d.begin() + static_cast<long>(kk), d.end());
  d.resize(kk);
  return d;
}

// The median log height of the k clouds nearest `z` (standardised).
double nearest_median(const std::vector<std::vector<double>>& clouds, const std::vector<double>& log_heights, const std::vector<double>& z, int k) {
  const std::vector<std::pair<double, size_t>> d = nearest(clouds, z, k);
  const size_t kk = d.size();
  std::vector<double> h;
  for (size_t j = 0; j < kk; ++j) h.push_back(log_heights[d[j].second]);
  std::sort(h.begin(), h.end());
  return kk % 2 ? h[kk / 2] : 0.5 * (h[kk / 2 - 1] + h[kk / 2]);
}

std::vector<double> standardised(const std::vector<double>& f, const std::vector<double>& mean, const std::vector<double>& stddev) {
  std::vector<double> z(f.size());
  for (size_t c = 0; c < f.size(); ++c) z[c] = (f[c] - mean[c]) / stddev[c];
  return z;
}

// sqrt(det) of the horizontal covariance of the endpoints in the lowest (or, `top`, the highest) kEndSlab of the
// height between `ground_z` and `top_z`; 0 for fewer than 3 endpoints there.
double end_spread(const std::vector<Segment3>& segments, double ground_z, double top_z, bool top) {
  const double cut = top ? top_z - kEndSlab * (top_z - ground_z) : ground_z + kEndSlab * (top_z - ground_z);
  double n = 0, mx = 0, my = 0;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b})
      if (top ? p.z() >= cut : p.z() <= cut) n += 1, mx += p.x(), my += p.y();
  if (n < 3) return 0.0;
  mx /= n, my /= n;
  double sxx = 0, syy = 0, sxy = 0;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b})
      if (top ? p.z() >= cut : p.z() <= cut) sxx += (p.x() - mx) * (p.x() - mx), syy += (p.y() - my) * (p.y() - my), sxy += (p.x() - mx) * (p.y() - my);
  sxx /= n, syy /= n, sxy /= n;
  return std::sqrt(std::max(0.0, sxx * syy - sxy * sxy));
}

// LineStatistics::ends of lines between `ground_z` and `top_z`.
std::vector<double> end_statistics(const std::vector<Segment3>& segments, double ground_z, double top_z) {
  const double h = top_z - ground_z, low = ground_z + kEndSlab * h, high = top_z - kEndSlab * h;
  double n_bottom = 0, n_top = 0, len_bottom = 0, len_top = 0, weighted = 0, total = 0;
  for (const Segment3& s : segments) {
    const double mid = 0.5 * (s.a.z() + s.b.z()), len = s.length();
    if (mid <= low) n_bottom += 1, len_bottom += len;
    if (mid >= high) n_top += 1, len_top += len;
    weighted += len * mid, total += len;
  }
  return {log_end_spread_ratio(segments, ground_z, top_z), std::log((n_bottom + 1) / (n_top + 1)),
          std::log((len_bottom + 1e-9 * h) / (len_top + 1e-9 * h)),
          total > 0 ? (0.5 * (ground_z + top_z) - weighted / total) / h : 0.0};
}

}  // namespace

double log_end_spread_ratio(const std::vector<Segment3>& segments, double ground_z, double top_z) {
  const double tiny = 1e-12 * (top_z - ground_z) * (top_z - ground_z);
  if (!(tiny > 0)) return 0.0;  // no height: neither end is the ground
  return std::log(std::max(end_spread(segments, ground_z, top_z, false), tiny) / std::max(end_spread(segments, ground_z, top_z, true), tiny));
}

LineStatistics line_statistics(const std::vector<Segment3>& segments, double ground_quantile, double top_quantile) {
  if (segments.size() < 10) throw std::invalid_argument("line statistics need at least 10 lines, got " + std::to_string(segments.size()));
  std::vector<double> z, x, y;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b}) z.push_back(p.z()), x.push_back(p.x()), y.push_back(p.y());
  LineStatistics out;
  const double ground_z = quantile(z, ground_quantile), top_z = quantile(z, top_quantile);
  out.height = top_z - ground_z;
  if (!(out.height > 0) || !std::isfinite(out.height)) throw std::invalid_argument("line statistics: the lines have no height");
  out.ends = end_statistics(segments, ground_z, top_z);
  out.features.assign(kLineStatisticsSize, 0.0);
  const double n = static_cast<double>(segments.size());
  for (const Segment3& s : segments) {
    const Vec3 d = s.b - s.a;
    const double len = d.norm();
    if (!(len > 0)) continue;
    const double c = std::abs(d.z()) / len;
    const int cls = c > kVerticalCos ? 0 : c < kHorizontalCos ? 1 : 2;
    const double rel = std::clamp(std::log2(len / out.height), kLowestLog2 + 0.01, -0.01);
    const int bin = std::clamp(static_cast<int>(std::floor((rel - kLowestLog2) / kBinLog2)), 0, kLineLengthBins - 1);
    out.features[cls * kLineLengthBins + bin] += 1.0 / n;
  }
  // The footprint's spreads: square roots of the eigenvalues of the endpoints' horizontal covariance. Plain
  // loops: a vectorised sum's order follows the buffer's alignment, and the statistics must not.
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  const double m = static_cast<double>(x.size());
  mx /= m, my /= m;
  double sxx = 0, syy = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) sxx += (x[i] - mx) * (x[i] - mx), syy += (y[i] - my) * (y[i] - my), sxy += (x[i] - mx) * (y[i] - my);
  sxx /= m, syy /= m, sxy /= m;
  const double tr = 0.5 * (sxx + syy), det = std::sqrt(std::max(0.0, 0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy));
  const double floor = 1e-12 * out.height * out.height;  // a single wall seen edge-on has no width, not log(0)
  out.features[3 * kLineLengthBins] = 0.5 * std::log(std::max(tr - det, floor)) - std::log(out.height);
  out.features[3 * kLineLengthBins + 1] = 0.5 * std::log(std::max(tr + det, floor)) - std::log(out.height);
  return out;
}

double HeightModel::predict_height_m(const LineStatistics& s) const {
  if (s.features.size() != mean.size())
    throw std::invalid_argument("height model: " + std::to_string(mean.size()) + " statistics expected, got " + std::to_string(s.features.size()));
  return std::exp(nearest_median(clouds, log_heights, standardised(s.features, mean, stddev), k));
}

double HeightModel::neighbour_distance(const LineStatistics& s) const {
  if (s.features.size() != mean.size())
    throw std::invalid_argument("height model: " + std::to_string(mean.size()) + " statistics expected, got " + std::to_string(s.features.size()));
  const std::vector<std::pair<double, size_t>> d = nearest(clouds, standardised(s.features, mean, stddev), k);
  double sum = 0;
  for (const auto& [d2, i] : d) sum += std::sqrt(d2);
  return sum / static_cast<double>(d.size());
}

std::optional<bool> HeightModel::upside_down(const LineStatistics& s) const {
  if (ends.empty()) return std::nullopt;
  if (s.ends.size() != ends_stddev.size())
    throw std::invalid_argument("height model: " + std::to_string(ends_stddev.size()) + " end statistics expected, got " + std::to_string(s.ends.size()));
  const std::vector<std::pair<double, size_t>> d = nearest(clouds, standardised(s.features, mean, stddev), k);
  double agreement = 0;  // (the cloud's ends) . (the neighbours' mean ends), both standardised
  for (size_t c = 0; c < ends_stddev.size(); ++c) {
    double neighbours = 0;
    for (const auto& [d2, i] : d) neighbours += ends[i][c];
    agreement += (s.ends[c] / ends_stddev[c]) * (neighbours / static_cast<double>(d.size()) / ends_stddev[c]);
  }
  return agreement < 0;
}

void HeightModel::Check() const {
  if (mean.size() != static_cast<size_t>(kLineStatisticsSize) || stddev.size() != mean.size())
    throw std::invalid_argument("height model: mean and stddev need " + std::to_string(kLineStatisticsSize) + " values each");
  for (size_t c = 0; c < mean.size(); ++c) {
    if (!std::isfinite(mean[c])) throw std::invalid_argument("height model: a non-finite mean");
    if (!(stddev[c] > 0) || !std::isfinite(stddev[c])) throw std::invalid_argument("height model: stddev must be positive and finite");
  }
  if (clouds.empty() || clouds.size() != log_heights.size()) throw std::invalid_argument("height model: one height per training cloud, and at least one");
  if (k < 1 || static_cast<size_t>(k) > clouds.size()) throw std::invalid_argument("height model: k must be in [1, training clouds]");
  if (!ends.empty() && ends.size() != clouds.size()) throw std::invalid_argument("height model: end statistics for every training cloud or none");
  if (!ends.empty() && ends_stddev.size() != static_cast<size_t>(kEndStatisticsSize)) throw std::invalid_argument("height model: ends_stddev needs " + std::to_string(kEndStatisticsSize) + " values");
  for (double v : ends_stddev)
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("height model: ends_stddev must be positive and finite");
  for (size_t i = 0; i < clouds.size(); ++i) {
    if (clouds[i].size() != mean.size()) throw std::invalid_argument("height model: training cloud " + std::to_string(i) + " has the wrong number of statistics");
    for (double v : clouds[i])
      if (!std::isfinite(v)) throw std::invalid_argument("height model: training cloud " + std::to_string(i) + " has a non-finite statistic");
    if (!ends.empty()) {
      if (ends[i].size() != static_cast<size_t>(kEndStatisticsSize)) throw std::invalid_argument("height model: training cloud " + std::to_string(i) + " has the wrong number of end statistics");
      for (double v : ends[i])
        if (!std::isfinite(v)) throw std::invalid_argument("height model: training cloud " + std::to_string(i) + " has a non-finite end statistic");
    }
    // 0.1 m to 10 km: anything else is not a building's height.
    if (!(log_heights[i] > std::log(0.1) && log_heights[i] < std::log(1e4)))
      throw std::invalid_argument("height model: training height " + std::to_string(i) + " out of range");
  }
}

void HeightFitOptions::Check() const {
  if (ks.empty()) throw std::invalid_argument("HeightFitOptions.ks must not be empty");
  for (int k : ks)
    if (k < 1 || k > 1000) throw std::invalid_argument("HeightFitOptions.ks must be in [1, 1000]");
  if (folds < 2 || folds > 100) throw std::invalid_argument("HeightFitOptions.folds must be in [2, 100]");
}

HeightModel fit_height_model(const std::vector<LineStatistics>& clouds, const std::vector<double>& heights_m, const HeightFitOptions& o) {
  o.Check();
  if (clouds.size() != heights_m.size()) throw std::invalid_argument("fit_height_model: one height per cloud");
  const size_t n = clouds.size();
  const int max_k = *std::max_element(o.ks.begin(), o.ks.end());
  if (n < static_cast<size_t>(o.folds) * static_cast<size_t>(max_k + 1))
    throw std::invalid_argument("fit_height_model: " + std::to_string(n) + " clouds are too few for " + std::to_string(o.folds) +
                                " folds of more than " + std::to_string(max_k) + " (the largest k)");
  std::vector<double> log_h(n);
  for (size_t i = 0; i < n; ++i) {
    if (clouds[i].features.size() != static_cast<size_t>(kLineStatisticsSize)) throw std::invalid_argument("fit_height_model: wrong number of statistics");
    if (!(heights_m[i] > 0) || !std::isfinite(heights_m[i])) throw std::invalid_argument("fit_height_model: heights must be positive");
    log_h[i] = std::log(heights_m[i]);
  }
  auto fold_of = [&](size_t i) { return static_cast<int>(i * static_cast<size_t>(o.folds) / n); };
  // Per fold: the standardisation and the standardised training and held-out clouds, shared by every k.
  std::vector<std::vector<std::vector<double>>> train(o.folds), held(o.folds);
  std::vector<std::vector<double>> train_h(o.folds), held_h(o.folds);
  for (int f = 0; f < o.folds; ++f) {
    std::vector<const std::vector<double>*> rows;
    for (size_t i = 0; i < n; ++i)
      if (fold_of(i) != f) rows.push_back(&clouds[i].features);
    std::vector<double> mean, stddev;
    standardisation(rows, &mean, &stddev);
    for (size_t i = 0; i < n; ++i) {
      auto& into = fold_of(i) == f ? held[f] : train[f];
      into.push_back(standardised(clouds[i].features, mean, stddev));
      (fold_of(i) == f ? held_h[f] : train_h[f]).push_back(log_h[i]);
    }
  }
  HeightModel m;
  double best = INFINITY;
  for (int k : o.ks) {
    std::vector<double> errors;
    for (int f = 0; f < o.folds; ++f)
      for (size_t j = 0; j < held[f].size(); ++j) errors.push_back(relative_error(nearest_median(train[f], train_h[f], held[f][j], k), held_h[f][j]));
    const double median = quantile(errors, 0.5);
    if (median < best) best = median, m.k = k, m.cv_median_error = median, m.cv_p90_error = quantile(errors, 0.9);
  }
  std::vector<const std::vector<double>*> rows;
  for (const LineStatistics& c : clouds) rows.push_back(&c.features);
  standardisation(rows, &m.mean, &m.stddev);
  for (const LineStatistics& c : clouds) m.clouds.push_back(standardised(c.features, m.mean, m.stddev));
  m.log_heights = log_h;
  m.ends_stddev.assign(kEndStatisticsSize, 0.0);
  for (const LineStatistics& c : clouds) {
    if (c.ends.size() != static_cast<size_t>(kEndStatisticsSize)) throw std::invalid_argument("fit_height_model: wrong number of end statistics");
    m.ends.push_back(c.ends);
    for (int e = 0; e < kEndStatisticsSize; ++e) m.ends_stddev[e] += c.ends[e] * c.ends[e] / static_cast<double>(n);
  }
  for (double& v : m.ends_stddev) v = v > 1e-18 ? std::sqrt(v) : 1.0;  // about 0: the sign is what counts
  m.Check();
  return m;
}

nlohmann::json height_model_json(const HeightModel& m) {
  nlohmann::json j = {{"format", "lc2wf-height-model"},
          {"version", 1},
          {"statistics", "line-statistics-v1"},
          {"k", m.k},
          {"cv_median_error", m.cv_median_error},
          {"cv_p90_error", m.cv_p90_error},
          {"mean", m.mean},
          {"stddev", m.stddev},
          {"log_heights", m.log_heights},
          {"clouds", m.clouds}};
  if (!m.ends.empty()) j["ends"] = m.ends, j["ends_stddev"] = m.ends_stddev;
  return j;
}

HeightModel height_model_from_json(const nlohmann::json& j, const std::string& source) {
  try {
    if (!j.is_object() || j.value("format", "") != "lc2wf-height-model") throw std::invalid_argument("not an lc2wf-height-model file");
    if (j.value("version", 0) != 1) throw std::invalid_argument("unsupported version (1 expected)");
    if (j.value("statistics", "") != "line-statistics-v1") throw std::invalid_argument("unknown statistics (line-statistics-v1 expected)");
    HeightModel m;
    m.k = j.at("k").get<int>();
    m.cv_median_error = j.value("cv_median_error", 0.0);
    m.cv_p90_error = j.value("cv_p90_error", 0.0);
    m.mean = j.at("mean").get<std::vector<double>>();
    m.stddev = j.at("stddev").get<std::vector<double>>();
    m.log_heights = j.at("log_heights").get<std::vector<double>>();
    m.clouds = j.at("clouds").get<std::vector<std::vector<double>>>();
    if (j.contains("ends")) {
      m.ends = j.at("ends").get<std::vector<std::vector<double>>>();
      m.ends_stddev = j.at("ends_stddev").get<std::vector<double>>();
    }
    m.Check();
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(source + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
}

HeightModel read_height_model(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, std::uintmax_t{64} << 20);  // statistics of ~1,000 clouds are ~1 MB
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) throw std::invalid_argument(path.string() + ": not valid JSON");
  return height_model_from_json(j, path.string());
}

std::optional<HeightModel> choose_height_model(const std::string& choice, const std::filesystem::path& weights_dir) {
  if (choice == "none") return std::nullopt;
  const std::filesystem::path path = choice.empty() ? weights_dir / kHeightModelFile : std::filesystem::path(choice);
  if (choice.empty() && !std::filesystem::exists(path)) return std::nullopt;
  return read_height_model(path);
}

void write_height_model(const std::filesystem::path& path, const HeightModel& m) {
  m.Check();
  write_text_atomically(path, json_text(height_model_json(m)) + "\n");  // one line: a thousand clouds of statistics
}

}  // namespace lc2wf
