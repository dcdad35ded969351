#include "tools/lines/lsd_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lc2wf {

void LsdOptions::Check() const {
  if (min_length_frac < 0 || min_length_frac >= 1) throw std::invalid_argument("LsdOptions.min_length_frac must be in [0, 1)");
  if (max_segments < 1) throw std::invalid_argument("LsdOptions.max_segments must be >= 1");
  if (max_side < 0) throw std::invalid_argument("LsdOptions.max_side must be >= 0");
  if (!(scale > 0 && scale <= 1)) throw std::invalid_argument("LsdOptions.scale must be in (0, 1]");
}

LsdOptions scaled_lsd(const LsdOptions& options, double scale) {
  LsdOptions o = options;
  if (!(scale > 1.0)) return o;
  o.min_length_frac = options.min_length_frac / scale;
  o.max_segments = static_cast<int>(std::min(std::lround(options.max_segments * scale * scale), 1L << 30));
  if (options.max_side > 0) o.max_side = static_cast<int>(std::lround(options.max_side * scale));
  return o;
}

std::vector<Segment2> detect_segments(const cv::Mat& image, const LsdOptions& options) {
  options.Check();
  if (image.empty()) throw std::invalid_argument("detect_segments: empty image");
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw std::invalid_argument("detect_segments: expected an 8-bit gray or BGR image");
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else
    gray = image;
  double scale = 1.0;
  const int side = std::max(gray.cols, gray.rows);
  if (options.max_side > 0 && side > options.max_side) {
    scale = static_cast<double>(options.max_side) / side;
    cv::resize(gray, gray, cv::Size(), scale, scale, cv::INTER_AREA);
  }
  cv::Ptr<cv::LineSegmentDetector> lsd =
      cv::createLineSegmentDetector(options.refine_advanced ? cv::LSD_REFINE_ADV : cv::LSD_REFINE_STD, options.scale);
  std::vector<cv::Vec4f> raw;
  lsd->detect(gray, raw);
  const double min_len = options.min_length_frac * std::hypot(image.cols, image.rows);
  // Map pixel centres back to full resolution (pixel-centre convention on both grids).
  auto up = [scale](double v) { return (v + 0.5) / scale - 0.5; };
  std::vector<Segment2> segs;
  segs.reserve(raw.size());
  for (const cv::Vec4f& r : raw) {
    Segment2 s{Vec2(up(r[0]), up(r[1])), Vec2(up(r[2]), up(r[3]))};
    if (s.length() > min_len) segs.push_back(s);
  }
  // Stable order on equal lengths keeps ids deterministic.
  std::stable_sort(segs.begin(), segs.end(), [](const Segment2& a, const Segment2& b) { return a.length() > b.length(); });
  if (static_cast<int>(segs.size()) > options.max_segments) segs.resize(options.max_segments);
  return segs;
}

}  // namespace lc2wf
