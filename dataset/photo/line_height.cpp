#include "dataset/photo/line_height.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "core/util/atomic_file.h"
#include "core/util/input_file.h"
#include "core/util/json_text.h"
#include "core/util/quantile.h"

namespace lc2wf {

namespace {

// |cos| of the angle to z: above this a line is near vertical, below the second near horizontal (10 deg each).
constexpr double kVerticalCos = 0.985, kHorizontalCos = 0.17;
constexpr double kLowestLog2 = -7.0, kBinLog2 = 0.5;

double relative_error(double predicted_log, double true_log) { return std::abs(std::exp(predicted_log - true_log) - 1.0); }

struct Standardised {
  Eigen::MatrixXd X;  // rows = clouds
  Eigen::VectorXd mean, stddev;
};

Standardised standardise(const Eigen::MatrixXd& raw) {
  Standardised s;
  s.mean = raw.colwise().mean();
  s.stddev = ((raw.rowwise() - s.mean.transpose()).array().square().colwise().mean()).sqrt().matrix().transpose();
  for (Eigen::Index k = 0; k < s.stddev.size(); ++k) s.stddev[k] += 1e-9;  // a constant feature gets weight 0, not NaN
  s.X = (raw.rowwise() - s.mean.transpose()).array().rowwise() / s.stddev.transpose().array();
  return s;
}

// Ridge on standardised features; the bias is not penalised (it is the mean target).
void solve_ridge(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, double lambda, Eigen::VectorXd* w, double* bias) {
  const Eigen::Index n = X.rows(), d = X.cols();
  Eigen::MatrixXd A(n, d + 1);
  A << X, Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd G = A.transpose() * A;
  for (Eigen::Index k = 0; k < d; ++k) G(k, k) += lambda;
  const Eigen::VectorXd sol = G.ldlt().solve(A.transpose() * y);
  *w = sol.head(d);
  *bias = sol[d];
}

}  // namespace

LineStatistics line_statistics(const std::vector<Segment3>& segments, double ground_quantile, double top_quantile) {
  if (segments.size() < 10) throw std::invalid_argument("line statistics need at least 10 lines, got " + std::to_string(segments.size()));
  std::vector<double> z, x, y;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b}) z.push_back(p.z()), x.push_back(p.x()), y.push_back(p.y());
  LineStatistics out;
  out.height = quantile(z, top_quantile) - quantile(z, ground_quantile);
  if (!(out.height > 0) || !std::isfinite(out.height)) throw std::invalid_argument("line statistics: the lines have no height");
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
  // The footprint's spreads: square roots of the eigenvalues of the endpoints' horizontal covariance.
  Eigen::Map<const Eigen::VectorXd> xs(x.data(), static_cast<Eigen::Index>(x.size())), ys(y.data(), static_cast<Eigen::Index>(y.size()));
  const double mx = xs.mean(), my = ys.mean(), m = static_cast<double>(x.size());
  const double sxx = (xs.array() - mx).square().sum() / m, syy = (ys.array() - my).square().sum() / m;
  const double sxy = ((xs.array() - mx) * (ys.array() - my)).sum() / m;
  const double tr = 0.5 * (sxx + syy), det = std::sqrt(std::max(0.0, 0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy));
  const double floor = 1e-12 * out.height * out.height;  // a single wall seen edge-on has no width, not log(0)
  out.features[3 * kLineLengthBins] = 0.5 * std::log(std::max(tr - det, floor)) - std::log(out.height);
  out.features[3 * kLineLengthBins + 1] = 0.5 * std::log(std::max(tr + det, floor)) - std::log(out.height);
  return out;
}

double HeightModel::predict_height_m(const LineStatistics& s) const {
  if (s.features.size() != weights.size())
    throw std::invalid_argument("height model: " + std::to_string(weights.size()) + " weights for " + std::to_string(s.features.size()) + " features");
  double log_h = bias;
  for (size_t k = 0; k < weights.size(); ++k) log_h += weights[k] * (s.features[k] - mean[k]) / stddev[k];
  return std::exp(log_h);
}

void HeightModel::Check() const {
  if (weights.size() != static_cast<size_t>(kLineStatisticsSize))
    throw std::invalid_argument("height model: weights has " + std::to_string(weights.size()) + " values, expected " + std::to_string(kLineStatisticsSize));
  if (mean.size() != weights.size() || stddev.size() != weights.size())
    throw std::invalid_argument("height model: mean, stddev and weights must have the same length");
  for (size_t k = 0; k < weights.size(); ++k) {
    if (!std::isfinite(mean[k]) || !std::isfinite(weights[k])) throw std::invalid_argument("height model: a non-finite mean or weight");
    if (!(stddev[k] > 0) || !std::isfinite(stddev[k])) throw std::invalid_argument("height model: stddev must be positive and finite");
  }
  // exp(bias) is the height at the mean features: outside 0.1-1000 m the file is not a building model.
  if (!(bias > std::log(0.1) && bias < std::log(1000.0))) throw std::invalid_argument("height model: bias (log metres) out of range");
}

void HeightFitOptions::Check() const {
  if (lambdas.empty()) throw std::invalid_argument("HeightFitOptions.lambdas must not be empty");
  for (double l : lambdas)
    if (!(l >= 0) || !std::isfinite(l)) throw std::invalid_argument("HeightFitOptions.lambdas must be finite and >= 0");
  if (folds < 2 || folds > 100) throw std::invalid_argument("HeightFitOptions.folds must be in [2, 100]");
}

HeightModel fit_height_model(const std::vector<LineStatistics>& clouds, const std::vector<double>& heights_m, const HeightFitOptions& o) {
  o.Check();
  if (clouds.size() != heights_m.size()) throw std::invalid_argument("fit_height_model: one height per cloud");
  if (clouds.size() < static_cast<size_t>(2 * o.folds)) throw std::invalid_argument("fit_height_model: at least 2 clouds per fold");
  const Eigen::Index n = static_cast<Eigen::Index>(clouds.size()), d = kLineStatisticsSize;
  Eigen::MatrixXd raw(n, d);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (clouds[i].features.size() != static_cast<size_t>(d)) throw std::invalid_argument("fit_height_model: wrong feature count");
    if (!(heights_m[i] > 0) || !std::isfinite(heights_m[i])) throw std::invalid_argument("fit_height_model: heights must be positive");
    for (Eigen::Index k = 0; k < d; ++k) raw(i, k) = clouds[i].features[k];
    y[i] = std::log(heights_m[i]);
  }
  HeightModel m;
  double best_median = INFINITY;
  for (double lambda : o.lambdas) {
    std::vector<double> errors;
    for (int f = 0; f < o.folds; ++f) {
      std::vector<Eigen::Index> train, held;
      for (Eigen::Index i = 0; i < n; ++i) (i % o.folds == f ? held : train).push_back(i);
      const Standardised s = standardise(raw(train, Eigen::all));
      Eigen::VectorXd w;
      double b = 0;
      solve_ridge(s.X, y(train), lambda, &w, &b);
      for (Eigen::Index i : held) {
        const Eigen::VectorXd z = (raw.row(i).transpose() - s.mean).cwiseQuotient(s.stddev);
        errors.push_back(relative_error(z.dot(w) + b, y[i]));
      }
    }
    const double median = quantile(errors, 0.5);
    if (median < best_median) best_median = median, m.lambda = lambda, m.cv_median_error = median, m.cv_p90_error = quantile(errors, 0.9);
  }
  const Standardised s = standardise(raw);
  Eigen::VectorXd w;
  solve_ridge(s.X, y, m.lambda, &w, &m.bias);
  m.mean.assign(s.mean.data(), s.mean.data() + d);
  m.stddev.assign(s.stddev.data(), s.stddev.data() + d);
  m.weights.assign(w.data(), w.data() + d);
  m.training_clouds = static_cast<int>(n);
  m.Check();
  return m;
}

nlohmann::json height_model_json(const HeightModel& m) {
  return {{"format", "lc2wf-height-model"},
          {"version", 1},
          {"features", "line-statistics-v1"},
          {"mean", m.mean},
          {"stddev", m.stddev},
          {"weights", m.weights},
          {"bias", m.bias},
          {"lambda", m.lambda},
          {"training_clouds", m.training_clouds},
          {"cv_median_error", m.cv_median_error},
          {"cv_p90_error", m.cv_p90_error}};
}

nlohmann::json line_height_json(double height_m, const std::string& why_not, const HeightModel& m) {
  nlohmann::json j = {{"used", why_not.empty() && height_m > 0},
                      {"cv_median_error", m.cv_median_error},
                      {"cv_p90_error", m.cv_p90_error},
                      {"training_clouds", m.training_clouds}};
  if (height_m > 0) j["height_m"] = height_m;
  if (!why_not.empty()) j["why_not"] = why_not;
  return j;
}

HeightModel height_model_from_json(const nlohmann::json& j, const std::string& source) {
  try {
    if (!j.is_object() || j.value("format", "") != "lc2wf-height-model") throw std::invalid_argument("not an lc2wf-height-model file");
    if (j.value("version", 0) != 1) throw std::invalid_argument("unsupported version (1 expected)");
    if (j.value("features", "") != "line-statistics-v1") throw std::invalid_argument("unknown features (line-statistics-v1 expected)");
    HeightModel m;
    m.mean = j.at("mean").get<std::vector<double>>();
    m.stddev = j.at("stddev").get<std::vector<double>>();
    m.weights = j.at("weights").get<std::vector<double>>();
    m.bias = j.at("bias").get<double>();
    m.lambda = j.value("lambda", 0.0);
    m.training_clouds = j.value("training_clouds", 0);
    m.cv_median_error = j.value("cv_median_error", 0.0);
    m.cv_p90_error = j.value("cv_p90_error", 0.0);
    m.Check();
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(source + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
}

HeightModel read_height_model(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, 1 << 20);
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) throw std::invalid_argument(path.string() + ": not valid JSON");
  return height_model_from_json(j, path.string());
}

std::optional<HeightModel> choose_height_model(const std::string& choice, const std::filesystem::path& weights_dir) {
  if (choice == "none") return std::nullopt;
  const std::filesystem::path path = choice.empty() ? weights_dir / kHeightModelFile : std::filesystem::path(choice);
  if (choice.empty() && !std::filesystem::exists(path)) return std::nullopt;
  try {
    return read_height_model(path);
  } catch (const std::runtime_error& e) {  // unreadable: read_input_file names the path
    throw std::invalid_argument(e.what());
  }
}

void write_height_model(const std::filesystem::path& path, const HeightModel& m) {
  m.Check();
  write_text_atomically(path, json_text(height_model_json(m), 1) + "\n");
}

}  // namespace lc2wf
