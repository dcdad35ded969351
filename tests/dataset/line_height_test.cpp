// A building's height from its line statistics (dataset/photo/line_height.h): the statistics do not change
// with the cloud's scale or place, a model fitted on hand-made facades (windows of one size, buildings of
// 1-15 storeys) reads the height of new ones back from their windows, never beyond the heights it was fitted
// on, and bad model files are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "dataset/photo/line_height.h"
#include "tests/common/constant_height_model.h"
#include "tests/common/windowed_box.h"

namespace lc2wf {
namespace {

using test::windowed_box;

std::vector<Segment3> moved(const std::vector<Segment3>& s, double scale, const Vec3& shift) {
  std::vector<Segment3> out;
  for (const Segment3& x : s) out.push_back({scale * x.a + shift, scale * x.b + shift});
  return out;
}

TEST(LineHeight, StatisticsIgnoreScaleAndPlace) {
  const std::vector<Segment3> s = windowed_box(4, 3.1, 17, 9, 3);
  const LineStatistics a = line_statistics(s), b = line_statistics(moved(s, 0.037, Vec3(512, -80, 3)));
  ASSERT_EQ(a.features.size(), static_cast<size_t>(kLineStatisticsSize));
  EXPECT_NEAR(b.height, 0.037 * a.height, 1e-9 * a.height);
  for (int k = 0; k < kLineStatisticsSize; ++k) EXPECT_NEAR(a.features[k], b.features[k], 1e-9) << "feature " << k;
  double shares = 0;
  for (int k = 0; k < 3 * kLineLengthBins; ++k) shares += a.features[k];
  EXPECT_NEAR(shares, 1.0, 1e-9);  // every line falls in one length bin of one direction class
}

TEST(LineHeight, LinesFallInTheirDirectionAndLengthBins) {
  std::vector<Segment3> s;
  for (int i = 0; i < 10; ++i) s.push_back({Vec3(i, 0, 0), Vec3(i, 0, 8)});    // full height, vertical: the last bin
  for (int i = 0; i < 10; ++i) s.push_back({Vec3(0, i, 4), Vec3(2, i, 4)});    // a quarter of it, horizontal
  const LineStatistics st = line_statistics(s, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(st.height, 8.0);
  EXPECT_DOUBLE_EQ(st.features[kLineLengthBins - 1], 0.5);
  EXPECT_DOUBLE_EQ(st.features[kLineLengthBins + 10], 0.5);  // log2(1/4) = -2: bin (−2 + 7) / 0.5
}

TEST(LineHeight, AModelFittedOnFacadesReadsTheHeightFromTheWindows) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> storeys(1, 15);
  std::uniform_real_distribution<double> storey_m(2.8, 3.4), side(8, 40), frame(0.01, 100);
  auto sample = [&](unsigned seed, std::vector<LineStatistics>* clouds, std::vector<double>* heights) {
    const std::vector<Segment3> metric = windowed_box(storeys(rng), storey_m(rng), side(rng), side(rng), seed);
    const LineStatistics m = line_statistics(metric);
    clouds->push_back(line_statistics(moved(metric, frame(rng), Vec3(3, 4, 5))));  // what the model sees: any frame
    heights->push_back(m.height);
  };
  std::vector<LineStatistics> train, test;
  std::vector<double> train_h, test_h;
  for (unsigned i = 0; i < 100; ++i) sample(i, &train, &train_h);
  for (unsigned i = 100; i < 120; ++i) sample(i, &test, &test_h);
  const HeightModel m = fit_height_model(train, train_h);
  EXPECT_EQ(m.clouds.size(), 100u);
  std::vector<double> errors;
  for (size_t i = 0; i < test.size(); ++i) errors.push_back(std::abs(m.predict_height_m(test[i]) / test_h[i] - 1));
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.15);
  // The heights span 2.8-51 m: the best constant guess (the training heights' median) misses by far more.
  std::vector<double> sorted_h = train_h, guess_errors;
  std::sort(sorted_h.begin(), sorted_h.end());
  for (double h : test_h) guess_errors.push_back(std::abs(sorted_h[sorted_h.size() / 2] / h - 1));
  std::sort(guess_errors.begin(), guess_errors.end());
  EXPECT_GT(guess_errors[guess_errors.size() / 2], 0.3);
  std::printf("height from the windows: median error %.3f (a constant guess %.3f)\n", errors[errors.size() / 2], guess_errors[guess_errors.size() / 2]);
  EXPECT_LT(m.cv_median_error, 0.15);
  // Written and read back, the model predicts the same.
  const auto path = std::filesystem::path(::testing::TempDir()) / "height_model_test.json";
  write_height_model(path, m);
  const HeightModel back = read_height_model(path);
  for (size_t i = 0; i < test.size(); ++i) EXPECT_DOUBLE_EQ(back.predict_height_m(test[i]), m.predict_height_m(test[i]));
  // However unlike the training clouds a cloud is, its height is one the model was fitted on.
  const double lowest = *std::min_element(train_h.begin(), train_h.end()), highest = *std::max_element(train_h.begin(), train_h.end());
  std::vector<Segment3> needle;
  for (int i = 0; i < 30; ++i) needle.push_back({Vec3(0, 0, 0), Vec3(0.01 * i, 0, 500)});
  const double h = m.predict_height_m(line_statistics(needle));
  EXPECT_GE(h, lowest);
  EXPECT_LE(h, highest);
  std::filesystem::remove(path);
}

// The end statistics change sign when a cloud is turned upside down; a fitted model keeps them (through its
// file too) and tells a turned cloud by its nearest clouds' ends, whichever end those say is the ground.
TEST(LineHeight, EndStatisticsTellWhichEndIsTheGround) {
  const std::vector<Segment3> facade = test::street_facade(4, 3.0, 20, 5);
  std::vector<Segment3> turned;
  for (const Segment3& x : facade) turned.push_back({Vec3(x.a.x(), -x.a.y(), -x.a.z()), Vec3(x.b.x(), -x.b.y(), -x.b.z())});
  const LineStatistics up = line_statistics(facade), down = line_statistics(turned);
  ASSERT_EQ(up.ends.size(), static_cast<size_t>(kEndStatisticsSize));
  for (int e = 0; e < kEndStatisticsSize; ++e) EXPECT_NEAR(up.ends[e], -down.ends[e], 1e-9) << "end statistic " << e;
  for (int k = 0; k < kLineStatisticsSize; ++k) EXPECT_NEAR(up.features[k], down.features[k], 1e-9) << "statistic " << k;
  EXPECT_GT(up.ends[1], 0.0);  // the lower storeys and the street hold more lines than the eaves

  const HeightModel m = height_model_from_json(height_model_json(test::street_facade_model(11)), "model.json");
  ASSERT_EQ(m.ends.size(), m.clouds.size());
  EXPECT_EQ(m.upside_down(up), std::optional<bool>(false));
  EXPECT_EQ(m.upside_down(down), std::optional<bool>(true));
}

TEST(LineHeight, BadInputsAndModelFilesAreRefused) {
  EXPECT_THROW(line_statistics({{Vec3(0, 0, 0), Vec3(1, 0, 1)}}), std::invalid_argument);  // too few lines
  std::vector<Segment3> flat;
  for (int i = 0; i < 20; ++i) flat.push_back({Vec3(i, 0, 0), Vec3(i, 1, 0)});
  EXPECT_THROW(line_statistics(flat), std::invalid_argument);  // no height
  HeightFitOptions bad;
  bad.folds = 1;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
  bad.folds = 5, bad.ks = {0};
  EXPECT_THROW(bad.Check(), std::invalid_argument);
  EXPECT_THROW(fit_height_model({}, {}), std::invalid_argument);

  const HeightModel m = test::constant_height_model(10.0);
  const nlohmann::json j = height_model_json(m);
  EXPECT_NO_THROW(height_model_from_json(j, "ok.json"));
  auto refused = [](nlohmann::json x, const std::string& what) {
    try {
      height_model_from_json(x, "model.json");
      ADD_FAILURE() << what << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("model.json"), std::string::npos) << e.what();
    }
  };
  nlohmann::json x = j;
  x["format"] = "lc2wf-model-card";
  refused(x, "another format");
  x = j, x["mean"].erase(0);
  refused(x, "a short mean");
  x = j, x["stddev"][3] = 0.0;
  refused(x, "a zero stddev");
  x = j, x["log_heights"][0] = 40.0;
  refused(x, "a training height of e^40 m");
  x = j, x["k"] = 2;
  refused(x, "more neighbours than training clouds");
  x = j, x["clouds"][0].erase(5);
  refused(x, "a training cloud with too few statistics");
  x = j, x.erase("mean");
  refused(x, "a missing key");
  // End statistics: optional (models fitted before them have none), but whole and finite when there.
  EXPECT_FALSE(height_model_from_json(j, "old.json").upside_down(line_statistics(windowed_box(3, 3.0, 12, 8, 1))).has_value());
  x = j, x["ends"] = nlohmann::json::array({{0.1, 0.2, 0.3}}), x["ends_stddev"] = {1.0, 1.0, 1.0, 1.0};
  refused(x, "a training cloud with too few end statistics");
  x = j, x["ends"] = nlohmann::json::array({{0.1, 0.2, 0.3, 0.4}}), x["ends_stddev"] = {1.0, 0.0, 1.0, 1.0};
  refused(x, "a zero end stddev");
  x = j, x["ends"] = nlohmann::json::array({{0.1, 0.2, 0.3, 0.4}});
  refused(x, "ends without their stddev");
  const auto path = std::filesystem::path(::testing::TempDir()) / "height_model_garbage.json";
  std::ofstream(path) << "{ not json";
  EXPECT_THROW(read_height_model(path), std::invalid_argument);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lc2wf
