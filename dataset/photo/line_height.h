// A building's height from the statistics of its lines, for photo clouds and line maps that no GPS, known
// distance, building height or storey rhythm scales. Windows, doors, storeys, roof tiles and eaves have sizes
// of their own that do not grow with the building, so the lengths of a cloud's lines relative to its height
// (by direction) and its footprint's proportions say how tall it is. The heights of the nearest clouds in
// those statistics among metric clouds of real and generated buildings (lc2wf-fit-height) read it back;
// experiments/README.md, "Height from line statistics", says how well.
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

// How the cloud's bottom end differs from its top: log(bottom / top) of the end slabs' spread (log_end_spread_ratio),
// of their line count and of their line length, and how far the length-weighted mean height lies below
// mid-height (over the height). Each changes sign when the cloud is turned upside down; which of them tells
// the ground depends on the capture (whole buildings: the footprint spreads widest; street photos: the lower
// storeys hold more lines), so the model's nearest clouds say how to read them (line_up.h).
constexpr int kEndStatisticsSize = 4;

struct LineStatistics {
  double height = 0;             // top minus ground quantile of the endpoint heights, the segments' units
  std::vector<double> features;  // kLineStatisticsSize values; the same when the cloud is turned upside down
  std::vector<double> ends;      // kEndStatisticsSize values
};

// log(bottom / top) of the end slabs' spread: sqrt(det) of the horizontal covariance of the endpoints in the
// lowest and the highest 15 % of the height between `ground_z` and `top_z` (each floored at 1e-12 height^2).
// z up. LineStatistics::ends[0]; also the ground's side for maps without a height model (line_up.h).
double log_end_spread_ratio(const std::vector<Segment3>& segments, double ground_z, double top_z);

// `segments`: z up, any scale and origin. Throws std::invalid_argument for fewer than 10 lines or no height.
LineStatistics line_statistics(const std::vector<Segment3>& segments, double ground_quantile = 0.01, double top_quantile = 0.99);

// The training clouds' statistics and heights: a cloud is as tall as the median of its k nearest training
// clouds (standardised statistics, Euclidean). Chosen over a ridge regression on validation clouds: photo
// and clean clouds lie apart in these statistics, and one linear map served only one of the looks
// (experiments/README.md, "Height from line statistics").
struct HeightModel {
  std::vector<double> mean, stddev;       // the statistics' standardisation, kLineStatisticsSize each
  std::vector<std::vector<double>> clouds;  // standardised statistics of the training clouds
  std::vector<double> log_heights;        // their heights, log metres
  int k = 5;                              // neighbours asked
  double cv_median_error = 0, cv_p90_error = 0;  // |predicted / true height - 1| over the folds
  // The training clouds' end statistics (z up) and their standard deviations; empty in models fitted before
  // they were kept.
  std::vector<std::vector<double>> ends;
  std::vector<double> ends_stddev;
  double predict_height_m(const LineStatistics& s) const;  // always within the training heights
  // Mean standardised distance to the k nearest training clouds: how much a cloud looks like the metric, z-up
  // clouds the model was fitted on (line_up.h turns a map in an arbitrary frame by it).
  double neighbour_distance(const LineStatistics& s) const;
  // Whether `s`'s cloud is upside down: its end statistics agree better, turned, with the mean of its k nearest
  // training clouds' (the statistics that find them are the same either way up). Empty without `ends`.
  std::optional<bool> upside_down(const LineStatistics& s) const;
  void Check() const;  // throws std::invalid_argument naming what is wrong (sizes, non-finite values)
};

struct HeightFitOptions {
  std::vector<int> ks = {3, 5, 7, 9, 11, 15};  // tried by cross-validation; the lowest median error wins
  int folds = 5;  // contiguous blocks of the clouds in their given order, so buildings of one tile or source
                  // (adjacent by name) are held out together rather than vouching for each other
  void Check() const;
};

// `clouds[i]` of a building `heights_m[i]` tall (its metric line statistics' height). Deterministic.
HeightModel fit_height_model(const std::vector<LineStatistics>& clouds, const std::vector<double>& heights_m, const HeightFitOptions& options = {});

nlohmann::json height_model_json(const HeightModel& m);
// Throws std::invalid_argument naming `source` and the problem.
HeightModel height_model_from_json(const nlohmann::json& j, const std::string& source);
HeightModel read_height_model(const std::filesystem::path& path);
void write_height_model(const std::filesystem::path& path, const HeightModel& m);  // atomically

// A weights folder's height model: the model lc2wf-fit-height fitted for the networks beside it.
inline constexpr const char* kHeightModelFile = "height.json";
// The model a command uses: `choice` "none" -> none; empty -> `weights_dir`/height.json when there is one;
// else the file `choice` (which must exist). Throws naming the file and the problem (std::runtime_error when
// it cannot be read, std::invalid_argument when it is not a height model).
std::optional<HeightModel> choose_height_model(const std::string& choice, const std::filesystem::path& weights_dir);

}  // namespace lc2wf
