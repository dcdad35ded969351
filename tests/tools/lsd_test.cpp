// LSD wrapper: pixel-centre convention, ordering, length filter and cap.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "tools/lines/lsd_detector.h"

namespace lc2wf {
namespace {

TEST(LsdDetector, FindsTheSidesOfARectangleLongestFirst) {
  cv::Mat img(240, 320, CV_8UC1, cv::Scalar(200));
  // Dark block covering pixel columns 100..219 and rows 60..139: its edges lie at x = 99.5 / 219.5 and
  // y = 59.5 / 139.5 in the pixel-centre convention.
  img(cv::Rect(100, 60, 120, 80)).setTo(40);
  const auto segs = detect_segments(img, LsdOptions{});
  ASSERT_GE(segs.size(), 4u);
  for (size_t i = 1; i < segs.size(); ++i) EXPECT_GE(segs[i - 1].length(), segs[i].length());
  int horizontal = 0, vertical = 0;
  for (const auto& s : segs) {
    if (s.length() < 60) continue;
    const Vec2 mid = 0.5 * (s.a + s.b);
    if (std::abs(s.a.y() - s.b.y()) < 1.0) {
      ++horizontal;
      EXPECT_LT(std::min(std::abs(mid.y() - 59.5), std::abs(mid.y() - 139.5)), 0.75);
    } else if (std::abs(s.a.x() - s.b.x()) < 1.0) {
      ++vertical;
      EXPECT_LT(std::min(std::abs(mid.x() - 99.5), std::abs(mid.x() - 219.5)), 0.75);
    }
  }
  EXPECT_EQ(horizontal, 2);
  EXPECT_EQ(vertical, 2);
}

TEST(LsdDetector, LengthFilterCapAndDownscaling) {
  cv::Mat img(480, 640, CV_8UC3, cv::Scalar(180, 180, 180));
  for (int k = 0; k < 12; ++k) cv::rectangle(img, cv::Rect(20 + 50 * k, 40, 20, 10 + 30 * k), cv::Scalar(30, 60, 90), cv::FILLED);
  LsdOptions o;
  o.max_segments = 5;
  EXPECT_EQ(detect_segments(img, o).size(), 5u);
  o.max_segments = 1000;
  o.min_length_frac = 0.25;  // 200 px
  for (const auto& s : detect_segments(img, o)) EXPECT_GT(s.length(), 200.0);
  o.min_length_frac = 0.01;
  o.max_side = 320;
  const auto small = detect_segments(img, o);
  ASSERT_FALSE(small.empty());
  EXPECT_GT(small.front().length(), 300.0);  // coordinates are back at full resolution
  EXPECT_THROW(detect_segments(cv::Mat(), o), std::invalid_argument);
  EXPECT_THROW(detect_segments(cv::Mat(10, 10, CV_32F), o), std::invalid_argument);
  EXPECT_TRUE(detect_segments(cv::Mat(100, 100, CV_8UC1, cv::Scalar(7)), o).empty());
}

TEST(LsdDetector, ScaledOptionsKeepTheLimitsOfTheSetImageSize) {
  LsdOptions o;
  o.max_segments = 1000;
  o.min_length_frac = 0.005;
  const LsdOptions same = scaled_lsd(o, 1.0);
  EXPECT_EQ(same.max_segments, 1000);
  EXPECT_EQ(same.min_length_frac, 0.005);
  const LsdOptions x3 = scaled_lsd(o, 3.0);  // 3 x the pixels per side: 9 x the area
  EXPECT_EQ(x3.max_segments, 9000);
  EXPECT_NEAR(x3.min_length_frac, 0.005 / 3, 1e-15);  // the same shortest length in set-size pixels
  EXPECT_EQ(x3.max_side, 0);                         // never downscaled stays so
  // A drawing at 3 x the resolution yields (about) the segments of the small one, at 3 x their length.
  cv::Mat small(240, 320, CV_8UC1, cv::Scalar(200)), large;
  cv::rectangle(small, cv::Rect(60, 50, 150, 100), cv::Scalar(40), cv::FILLED);
  cv::resize(small, large, cv::Size(), 3.0, 3.0, cv::INTER_NEAREST);
  const auto a = detect_segments(small, o), b = detect_segments(large, x3);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_NEAR(b.front().length(), 3.0 * a.front().length(), 0.05 * 3.0 * a.front().length());
}

}  // namespace
}  // namespace lc2wf
