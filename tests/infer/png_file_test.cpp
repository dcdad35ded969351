// The previews' PNG encoder against an independent decoder (OpenCV's codecs, which only the tests load).
#include "infer/png_file.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <stdexcept>

namespace lc2wf {
namespace {

TEST(PngFile, DecodesToTheSamePixels) {
  const int width = 37, height = 11;  // rows of an odd byte count: no padding may slip in
  std::vector<uint8_t> rgb(3 * width * height);
  for (size_t k = 0; k < rgb.size(); ++k) rgb[k] = static_cast<uint8_t>((k * 7919) % 251);
  const std::string png = encode_png_rgb(rgb, width, height);
  const std::vector<uint8_t> bytes(png.begin(), png.end());
  const cv::Mat image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.cols, width);
  ASSERT_EQ(image.rows, height);
  ASSERT_EQ(image.type(), CV_8UC3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)  // OpenCV decodes to BGR
        ASSERT_EQ(image.at<cv::Vec3b>(y, x)[2 - c], rgb[3 * (y * width + x) + c]) << x << "," << y << " channel " << c;
}

TEST(PngFile, RefusesSizesThatDoNotFit) {
  EXPECT_THROW(encode_png_rgb({}, 0, 1), std::invalid_argument);
  EXPECT_THROW(encode_png_rgb(std::vector<uint8_t>(3 * 4 * 4 - 1), 4, 4), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
