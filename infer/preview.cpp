#include "infer/preview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/util/atomic_file.h"
#include "core/util/quantile.h"
#include "infer/png_file.h"

namespace lc2wf {

void PreviewOptions::Check() const {
  if (width < 64 || width > 8192) throw std::invalid_argument("PreviewOptions.width must be in [64, 8192]");
  if (height < 64 || height > 8192) throw std::invalid_argument("PreviewOptions.height must be in [64, 8192]");
  if (!(elevation_deg >= -90 && elevation_deg <= 90)) throw std::invalid_argument("PreviewOptions.elevation_deg must be in [-90, 90]");
  if (!std::isfinite(azimuth_deg)) throw std::invalid_argument("PreviewOptions.azimuth_deg must be finite");
  if (!(cloud_frame_quantile >= 0 && cloud_frame_quantile < 0.5))
    throw std::invalid_argument("PreviewOptions.cloud_frame_quantile must be in [0, 0.5)");
}

namespace {

// Screen coordinates (x right, y up) of a world point seen from (azimuth, elevation).
struct Oblique {
  Eigen::Matrix<double, 2, 3> m;
  explicit Oblique(const PreviewOptions& o) {
    const double a = o.azimuth_deg * M_PI / 180.0, e = o.elevation_deg * M_PI / 180.0;
    const Vec3 right(std::cos(a), -std::sin(a), 0.0);
    const Vec3 view(std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), -std::sin(e));  // into the scene
    const Vec3 up = right.cross(view).normalized();
    m.row(0) = right.transpose();
    m.row(1) = up.transpose();
  }
  Vec2 operator()(const Vec3& p) const { return m * p; }
};

}  // namespace

void write_preview(const std::filesystem::path& png, const LineCloud& cloud, const Wireframe& prediction,
                   const Wireframe* gt, const PreviewOptions& o) {
  o.Check();
  const Oblique project(o);
  // The frame holds the wireframes and the bulk of the cloud: a few triangulation outliers hundreds of metres
  // off would otherwise shrink the building to a dot (they are drawn where they fall in the frame).
  Vec2 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()), hi = -lo;
  auto grow = [&](const Vec2& q) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  };
  std::vector<double> xs, ys;
  for (const Segment3& s : cloud.segments)
    for (const Vec3* p : {&s.a, &s.b})
      if (p->allFinite()) {
        const Vec2 q = project(*p);
        xs.push_back(q.x()), ys.push_back(q.y());
      }
  if (!xs.empty()) {
    grow({quantile(xs, o.cloud_frame_quantile), quantile(ys, o.cloud_frame_quantile)});
    grow({quantile(xs, 1 - o.cloud_frame_quantile), quantile(ys, 1 - o.cloud_frame_quantile)});
  }
  for (const Wireframe* w : {&prediction, gt})
    if (w)
      for (const Vec3& p : w->junctions)
        if (p.allFinite()) grow(project(p));
  if (!(lo.x() <= hi.x())) lo = hi = Vec2::Zero();  // nothing to draw: an empty frame

  const double margin = 40.0;
  const Vec2 extent = (hi - lo).cwiseMax(Vec2(1e-6, 1e-6));
  const double scale = std::min((o.width - 2 * margin) / extent.x(), (o.height - 2 * margin) / extent.y());
  const Vec2 centre = (lo + hi) / 2;
  auto pixel = [&](const Vec3& p) {
    const Vec2 q = (project(p) - centre) * scale;
    return cv::Point2d(o.width / 2.0 + q.x(), o.height / 2.0 - q.y());
  };
  // OpenCV colours are BGR.
  const cv::Scalar grey(170, 170, 170), green(40, 160, 40), red(30, 30, 220), black(20, 20, 20);
  cv::Mat image(o.height, o.width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (const Segment3& s : cloud.segments)
    if (s.a.allFinite() && s.b.allFinite()) cv::line(image, pixel(s.a), pixel(s.b), grey, 1, cv::LINE_AA);
  auto draw = [&](const Wireframe& w, const cv::Scalar& colour, int thickness) {
    for (const auto& [a, b] : w.edges) cv::line(image, pixel(w.junctions[a]), pixel(w.junctions[b]), colour, thickness, cv::LINE_AA);
    for (const auto& [a, b] : w.edges)
      for (int k : {a, b}) cv::circle(image, pixel(w.junctions[k]), thickness + 1, colour, cv::FILLED, cv::LINE_AA);
  };
  if (gt) draw(*gt, green, 3);
  draw(prediction, red, 2);

  const std::string title = cloud.name + ": " + std::to_string(prediction.edges.size()) + " predicted edges" +
                            (gt ? ", " + std::to_string(gt->edges.size()) + " GT edges" : std::string());
  // Long building names (city models' ids) would run off the picture: the title shrinks to fit its width.
  double title_scale = 0.6;
  int baseline = 0;
  const double title_width = cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, title_scale, 1, &baseline).width;
  if (title_width > o.width - 24) title_scale *= (o.width - 24) / title_width;
  cv::putText(image, title, {12, 24}, cv::FONT_HERSHEY_SIMPLEX, title_scale, black, 1, cv::LINE_AA);
  int y = 48;
  for (const auto& [label, colour] : std::vector<std::pair<std::string, cv::Scalar>>{
           {"line cloud", grey}, {"prediction", red}, {"ground truth", green}}) {
    if (label == "ground truth" && !gt) continue;
    cv::line(image, {12, y - 5}, {36, y - 5}, colour, 3, cv::LINE_AA);
    cv::putText(image, label, {44, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, black, 1, cv::LINE_AA);
    y += 20;
  }

  cv::Mat rgb;
  cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);  // a new matrix: continuous, rows unpadded
  const std::string bytes = encode_png_rgb(std::vector<uint8_t>(rgb.datastart, rgb.dataend), o.width, o.height);
  write_file_atomically(png, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace lc2wf
