#include "dataset/photo/metric_frame.h"

#include "core/util/number_format.h"
#include "core/util/quantile.h"
#include "dataset/photo/line_up.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {

Camera Similarity::apply(const Camera& c) const {
  // x_cam is unchanged up to the factor `scale`, which the projection divides out.
  Camera out = c;
  out.R = c.R * R.transpose();
  out.t = scale * c.t - out.R * t;
  return out;
}

MetricFrame MetricFrame::scaled_by(double factor) const {
  MetricFrame f = *this;
  f.to_metric.scale *= factor;
  f.to_metric.t *= factor;
  return f;
}

Similarity Similarity::inverse() const {
  Similarity inv;
  inv.scale = 1.0 / scale;
  inv.R = R.transpose();
  inv.t = -inv.scale * inv.R * t;
  return inv;
}

void MetricFrameOptions::Check() const {
  if (!(vertical_line_max_deg > 0 && vertical_line_max_deg < 90)) throw std::invalid_argument("MetricFrameOptions.vertical_line_max_deg must be in (0, 90)");
  if (min_vertical_lines < 1) throw std::invalid_argument("MetricFrameOptions.min_vertical_lines must be >= 1");
  if (!(scale >= 0) || !std::isfinite(scale)) throw std::invalid_argument("MetricFrameOptions.scale must be >= 0");
  if (known_distance_m < 0 || !std::isfinite(known_distance_m)) throw std::invalid_argument("MetricFrameOptions.known_distance_m must be >= 0");
  if (known_distance_m > 0 && (known_view_a < 0 || known_view_b < 0 || known_view_a == known_view_b))
    throw std::invalid_argument("MetricFrameOptions: a known distance needs two different views");
  if (!(building_height_m >= 0) || !std::isfinite(building_height_m)) throw std::invalid_argument("MetricFrameOptions.building_height_m must be >= 0");
  if (gps_to_enu && !(gps_to_enu->scale > 0 && std::isfinite(gps_to_enu->scale) && gps_to_enu->R.allFinite()))
    throw std::invalid_argument("MetricFrameOptions.gps_to_enu is not a similarity");
  if (height_model) height_model->Check();
  if (!(max_storey_disagreement >= 1) || !std::isfinite(max_storey_disagreement))
    throw std::invalid_argument("MetricFrameOptions.max_storey_disagreement must be >= 1");
  if (!(ground_quantile >= 0 && ground_quantile < top_quantile && top_quantile <= 1))
    throw std::invalid_argument("MetricFrameOptions: need 0 <= ground_quantile < top_quantile <= 1");
  if (up == UpSource::kGiven && !(given_up.norm() > 0)) throw std::invalid_argument("MetricFrameOptions.given_up is zero");
  storeys.Check();
}

namespace {

// OpenCV cameras: image y points down, so the camera's up in the world is -(second row of R).
Vec3 mean_camera_up(const std::vector<Camera>& cameras) {
  Vec3 sum = Vec3::Zero();
  for (const Camera& c : cameras) sum -= c.R.row(1).transpose();
  if (sum.norm() < 1e-9) throw std::invalid_argument("the cameras' up vectors cancel out: no up direction");
  return sum.normalized();
}

// Length-weighted principal direction of the lines within max_deg of `up`; count = lines used.
Vec3 refine_with_vertical_lines(const Vec3& up, const std::vector<Segment3>& segments, double max_deg, int* count) {
  const double cos_max = std::cos(max_deg * M_PI / 180.0);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  *count = 0;
  for (const Segment3& s : segments) {
    const double len = s.length();
    if (len <= 0) continue;
    const Vec3 d = (s.b - s.a) / len;
    if (std::abs(d.dot(up)) < cos_max) continue;
    scatter += len * d * d.transpose();
    ++*count;
  }
  if (*count == 0) return up;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Vec3 v = eig.eigenvectors().col(2);
  return v.dot(up) < 0 ? Vec3(-v) : v;
}

// Lines turned z up over their ground, in input units: what the storey rhythm and the line statistics are read from.
std::vector<Segment3> upright_lines(const std::vector<Segment3>& segments, const Eigen::Matrix3d& R, double ground) {
  std::vector<Segment3> upright;
  upright.reserve(segments.size());
  for (const Segment3& s : segments) upright.push_back({R * s.a - ground * Vec3::UnitZ(), R * s.b - ground * Vec3::UnitZ()});
  return upright;
}

}  // namespace

MetricFrame estimate_metric_frame(const std::vector<Camera>& cameras, const std::vector<Segment3>& segments,
                                  const MetricFrameOptions& o, const std::vector<Segment3>* storey_lines) {
  o.Check();
  if (segments.empty()) throw std::invalid_argument("estimate_metric_frame: no 3D line");
  MetricFrame f;
  switch (o.up) {
    case UpSource::kInputZ:
      f.up_input = Vec3::UnitZ(), f.up_source = "input z";
      break;
    case UpSource::kGiven:
      f.up_input = o.given_up.normalized(), f.up_source = "given";
      break;
    case UpSource::kLines:
    case UpSource::kCameras:
    case UpSource::kAuto: {
      const bool from_gps = o.up == UpSource::kAuto && o.gps_to_enu;
      const bool from_lines = o.up == UpSource::kLines || (o.up == UpSource::kAuto && !from_gps && cameras.empty());
      if (from_gps) {
        f.up_input = (o.gps_to_enu->R.transpose() * Vec3::UnitZ()).normalized(), f.up_source = "gps";
      } else if (from_lines) {
        f.line_up = up_from_lines(segments, o.height_model ? &*o.height_model : nullptr);
        f.up_input = f.line_up->up, f.up_source = "line directions";
      } else {
        if (cameras.empty()) throw std::invalid_argument("estimate_metric_frame: no camera to take the up direction from");
        f.up_input = mean_camera_up(cameras), f.up_source = "cameras";
      }
      if (o.up != UpSource::kCameras) {
        int count = 0;
        const Vec3 refined = refine_with_vertical_lines(f.up_input, segments, o.vertical_line_max_deg, &count);
        if (count >= o.min_vertical_lines) f.up_input = refined, f.up_source += "+lines", f.vertical_lines = count;
      }
      break;
    }
  }
  // With GPS, x east and y north: the GPS rotation, tilted by the refinement of its up.
  const Eigen::Matrix3d R =
      o.gps_to_enu && f.up_source.rfind("gps", 0) == 0
          ? Eigen::Matrix3d(Eigen::Quaterniond::FromTwoVectors(o.gps_to_enu->R * f.up_input, Vec3::UnitZ()).toRotationMatrix() * o.gps_to_enu->R)
          : Eigen::Matrix3d(Eigen::Quaterniond::FromTwoVectors(f.up_input, Vec3::UnitZ()).toRotationMatrix());

  std::vector<double> heights, mid_x, mid_y;
  for (const Segment3& s : segments) {
    const Vec3 a = R * s.a, b = R * s.b;
    heights.push_back(a.z());
    heights.push_back(b.z());
    mid_x.push_back(0.5 * (a.x() + b.x()));
    mid_y.push_back(0.5 * (a.y() + b.y()));
  }
  const double ground = quantile(heights, o.ground_quantile);
  f.height_input = quantile(heights, o.top_quantile) - ground;

  double scale = o.scale;
  f.scale_source = "given";
  if (scale == 0 && o.known_distance_m > 0) {
    if (o.known_view_a >= static_cast<int>(cameras.size()) || o.known_view_b >= static_cast<int>(cameras.size()))
      throw std::invalid_argument("estimate_metric_frame: known-distance view out of range");
    const double d = (cameras[o.known_view_a].center() - cameras[o.known_view_b].center()).norm();
    if (!(d > 0)) throw std::invalid_argument("estimate_metric_frame: the two known-distance cameras coincide");
    scale = o.known_distance_m / d, f.scale_source = "known distance";
  }
  if (scale == 0 && o.gps_to_enu) scale = o.gps_to_enu->scale, f.scale_source = "gps";
  if (scale == 0) {
    if (!(f.height_input > 0)) throw std::invalid_argument("estimate_metric_frame: the cloud has no height to take a scale from");
    if (o.building_height_m > 0) {
      scale = o.building_height_m / f.height_input, f.scale_source = "building height";
    } else {
      const std::vector<Segment3> upright = upright_lines(storey_lines ? *storey_lines : segments, R, ground);
      f.storeys = estimate_storey_scale(upright, f.height_input, o.storeys);
      double model_scale = 0;
      if (o.height_model) {
        try {
          const LineStatistics stats = line_statistics(upright, o.ground_quantile, o.top_quantile);
          f.line_height_m = o.height_model->predict_height_m(stats);
          model_scale = f.line_height_m / stats.height;
        } catch (const std::invalid_argument& e) {
          f.line_height_why_not = e.what();
        }
      }
      const double disagreement = model_scale > 0 && f.storeys.found
                                      ? std::max(f.storeys.metres_per_unit / model_scale, model_scale / f.storeys.metres_per_unit)
                                      : 1.0;
      if (f.storeys.found && disagreement <= o.max_storey_disagreement) {
        scale = f.storeys.metres_per_unit, f.scale_source = "storeys";
      } else if (model_scale > 0) {
        if (f.storeys.found)
          f.storeys_overruled = "the storeys make the building " + std::to_string(disagreement) + "x " +
                                (f.storeys.metres_per_unit > model_scale ? "taller" : "lower") + " than the height model reads";
        scale = model_scale, f.scale_source = "line statistics";
      } else {
        scale = 1.0 / f.height_input, f.scale_source = "scale search", f.needs_scale_search = true;
      }
    }
  }
  f.to_metric.scale = scale;
  f.to_metric.R = R;
  f.to_metric.t = -scale * Vec3(quantile(mid_x, 0.5), quantile(mid_y, 0.5), ground);
  return f;
}

bool storeys_consulted(const MetricFrame& f) {
  return f.needs_scale_search || f.scale_source == "storeys" || f.scale_source == "line statistics";
}

std::string line_height_text(const MetricFrame& f, const HeightModel& m) {
  return "building height " + format_number("%.1f", f.line_height_m) + " m read from the lines (+-" +
         format_number("%.0f", 100 * m.cv_median_error) + " % median)" + (f.storeys_overruled.empty() ? "" : "; " + f.storeys_overruled);
}

nlohmann::json line_height_json(const MetricFrame& f, const HeightModel& m) {
  nlohmann::json j = {{"used", f.scale_source == "line statistics"},
                      {"cv_median_error", m.cv_median_error},
                      {"cv_p90_error", m.cv_p90_error},
                      {"training_clouds", m.clouds.size()},
                      {"neighbours", m.k}};
  if (f.line_height_m > 0) j["height_m"] = f.line_height_m;
  if (!f.line_height_why_not.empty()) j["why_not"] = f.line_height_why_not;
  if (!f.storeys_overruled.empty()) j["storeys_overruled"] = f.storeys_overruled;
  return j;
}

}  // namespace lc2wf
