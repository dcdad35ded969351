// A building's height from the statistics of its lines, for photo clouds and line maps that no GPS, known
// distance, building height or storey rhythm scales. Windows, doors, storeys, roof tiles and eaves have sizes
// of their own that do not grow with the building, so the lengths of a cloud's lines relative to its height
// (by direction) and its footprint's proportions say how tall it is. A ridge regression from those statistics
// to log(height), fitted on metric clouds of real and generated buildings of 3-60 m (lc2wf-fit-height), reads
// it back; experiments/README.md, "Height from line statistics", says how well.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Per direction class (near vertical, near horizontal, other) the share of all lines in each half-octave of
// length / height from 2^-7 to 1, then the log of the footprint's two spreads over the height. Scale- and
// shift-invariant; the line count is left out on purpose (it follows the number and size of the photos).
constexpr int kLineLengthBins = 14;
constexpr int kLineStatisticsSize = 3 * kLineLengthBins + 2;

struct LineStatistics {
  double height = 0;             // top minus ground quantile of the endpoint heights, the segments' units
  std::vector<double> features;  // kLineStatisticsSize values
};

// `segments`: z up, any scale and origin. Throws std::invalid_argument for fewer than 10 lines or no height.
LineStatistics line_statistics(const std::vector<Segment3>& segments, double ground_quantile = 0.01, double top_quantile = 0.99);

struct HeightModel {
  std::vector<double> mean, stddev;  // the features' standardisation
  std::vector<double> weights;       // on standardised features
  double bias = 0;                   // log(height in metres) at the mean features
  double lambda = 0;                 // the ridge penalty the cross-validation chose
  int training_clouds = 0;
  double cv_median_error = 0, cv_p90_error = 0;  // |predicted / true height - 1| over the folds
  double predict_height_m(const LineStatistics& s) const;
  void Check() const;  // throws std::invalid_argument naming what is wrong (sizes, non-finite values)
};

struct HeightFitOptions {
  std::vector<double> lambdas = {1, 3, 10, 30, 100, 300};  // tried by cross-validation; the lowest median error wins
  int folds = 5;                                           // clouds go to folds by their index, i % folds
  void Check() const;
};

// `clouds[i]` of a building `heights_m[i]` tall (its metric line statistics' height). Deterministic.
HeightModel fit_height_model(const std::vector<LineStatistics>& clouds, const std::vector<double>& heights_m, const HeightFitOptions& options = {});

nlohmann::json height_model_json(const HeightModel& m);
// What report.json says of a height read by `m` (or why none was): the height and the model's
// cross-validated errors, its uncertainty.
nlohmann::json line_height_json(double height_m, const std::string& why_not, const HeightModel& m);
// Throws std::invalid_argument naming `source` and the problem.
HeightModel height_model_from_json(const nlohmann::json& j, const std::string& source);
HeightModel read_height_model(const std::filesystem::path& path);
void write_height_model(const std::filesystem::path& path, const HeightModel& m);  // atomically

// A weights folder's height model: the model lc2wf-fit-height fitted for the networks beside it.
inline constexpr const char* kHeightModelFile = "height.json";
// The model a command uses: `choice` "none" -> none; empty -> `weights_dir`/height.json when there is one;
// else the file `choice` (which must exist). Throws std::invalid_argument naming the file and the problem.
std::optional<HeightModel> choose_height_model(const std::string& choice, const std::filesystem::path& weights_dir);

}  // namespace lc2wf
