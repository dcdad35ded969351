// infer/preview: the frame fits the building, not the triangulation outliers far off it; the title fits the width.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "infer/preview.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

// A 10 x 6 x 4 m box: its 12 edges as the wireframe, each edge as a cloud segment.
Wireframe box() {
  Wireframe w;
  for (double z : {0.0, 4.0})
    for (auto [x, y] : {std::pair{0.0, 0.0}, {10.0, 0.0}, {10.0, 6.0}, {0.0, 6.0}}) w.junctions.emplace_back(x, y, z);
  for (int k = 0; k < 4; ++k) w.edges.push_back({k, (k + 1) % 4}), w.edges.push_back({k + 4, (k + 1) % 4 + 4}), w.edges.push_back({k, k + 4});
  return w;
}

LineCloud cloud_of(const Wireframe& w) {
  LineCloud c;
  c.name = "box";
  for (const auto& [a, b] : w.edges) c.segments.push_back({w.junctions[a], w.junctions[b]});
  return c;
}

// Width of the columns holding green (ground-truth) pixels, as a share of the image width; the legend's
// corner (top left) does not count.
double green_width_share(const fs::path& png) {
  const cv::Mat image = cv::imread(png.string());  // BGR
  int first = image.cols, last = -1;
  for (int y = 0; y < image.rows; ++y)
    for (int x = y < 100 ? 160 : 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (p[1] > 120 && p[0] < 90 && p[2] < 90) first = std::min(first, x), last = std::max(last, x);
    }
  return last < first ? 0.0 : static_cast<double>(last - first) / image.cols;
}

class Preview : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lc2wf_preview_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(Preview, OutliersFarOffDoNotShrinkTheBuilding) {
  const Wireframe gt = box();
  LineCloud cloud = cloud_of(gt);
  const double clean = (write_preview(dir_ / "clean.png", cloud, gt, &gt), green_width_share(dir_ / "clean.png"));
  // A triangulated cloud: many segments on the building, a few hundreds of metres off it.
  for (int k = 0; k < 20; ++k) cloud.segments.insert(cloud.segments.end(), cloud.segments.begin(), cloud.segments.begin() + 12);
  cloud.segments.push_back({Vec3(400, -300, -50), Vec3(401, -300, -50)});
  cloud.segments.push_back({Vec3(-350, 500, 90), Vec3(-350, 501, 90)});
  write_preview(dir_ / "outliers.png", cloud, gt, &gt);
  EXPECT_GT(clean, 0.6);
  EXPECT_NEAR(green_width_share(dir_ / "outliers.png"), clean, 0.02);
  // Every segment end in the frame (quantile 0): the building shrinks, as before the rule.
  PreviewOptions every_end;
  every_end.cloud_frame_quantile = 0;
  write_preview(dir_ / "every.png", cloud, gt, &gt, every_end);
  EXPECT_LT(green_width_share(dir_ / "every.png"), 0.1);
}

TEST_F(Preview, APredictionOutsideTheCloudStaysInTheFrame) {
  const Wireframe gt = box();
  Wireframe far = gt;
  for (Vec3& p : far.junctions) p += Vec3(0, 0, 30);  // drawn 30 m above every line
  write_preview(dir_ / "far.png", cloud_of(gt), far, &gt);
  const cv::Mat image = cv::imread((dir_ / "far.png").string());
  int red_rows = 0;  // rows with red (prediction) pixels: the raised box is drawn, not clipped away
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (p[2] > 180 && p[1] < 80 && p[0] < 80) {
        ++red_rows;
        break;
      }
    }
  EXPECT_GT(red_rows, 50);
  EXPECT_GT(green_width_share(dir_ / "far.png"), 0.1);
}

TEST_F(Preview, ALongNameFitsTheTitleLine) {
  const Wireframe gt = box();
  LineCloud cloud = cloud_of(gt);
  cloud.name = std::string(120, 'W');  // a city model's file stem and building id run this long
  write_preview(dir_ / "long.png", cloud, gt, &gt);
  const cv::Mat image = cv::imread((dir_ / "long.png").string());
  int dark_left = 0, dark_right = 0;  // title pixels in the first and the last 10 columns of its line
  for (int y = 8; y < 30; ++y)
    for (int x = 0; x < 10; ++x) {
      dark_left += image.at<cv::Vec3b>(y, 12 + x)[0] < 100;
      dark_right += image.at<cv::Vec3b>(y, image.cols - 1 - x)[0] < 100;
    }
  EXPECT_GT(dark_left, 0);
  EXPECT_EQ(dark_right, 0);
}

TEST_F(Preview, EmptyCloudAndBadOptions) {
  const LineCloud empty;
  EXPECT_NO_THROW(write_preview(dir_ / "empty.png", empty, Wireframe{}, nullptr));
  EXPECT_TRUE(fs::exists(dir_ / "empty.png"));
  PreviewOptions bad;
  bad.cloud_frame_quantile = 0.5;
  EXPECT_THROW(write_preview(dir_ / "bad.png", empty, Wireframe{}, nullptr, bad), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
