#include "reconstruct/reconstruct_pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <cstdio>
#include <optional>

#include "core/parallel.h"
#include "core/util/json_text.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/line_obj_io.h"
#include "core/util/number_format.h"
#include "dataset/photo/camera_coverage.h"
#include "dataset/photo/exif_focal.h"
#include "dataset/photo/exif_gps.h"
#include "dataset/photo/exif_tiff.h"
#include "dataset/photo/local_enu.h"
#include "model/inference.h"
#include "model/scale_search.h"
#include "infer/prediction_io.h"
#include "infer/preview.h"
#include "infer/surfaces/surface_writers.h"
#include "infer/surfaces/wireframe_surfaces.h"
#include "reconstruct/camera_sources.h"
#include "reconstruct/image_folder.h"
#include "reconstruct/stage_error.h"
#include "core/util/workspace.h"

#include "core/util/seconds_since.h"
#include "core/util/version_json.h"

namespace lc2wf {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

using Clock = std::chrono::steady_clock;


class StageLog {
 public:
  explicit StageLog(bool quiet) : quiet_(quiet) {}
  void start(const std::string& stage) {
    stage_ = stage;
    t_ = Clock::now();
    if (!quiet_) std::fprintf(stderr, "lc2wf-reconstruct: %s ...\n", stage.c_str());
  }
  // Records the stage's seconds in the report and prints what it produced.
  void done(Json& seconds, const std::string& detail) {
    const double s = seconds_since(t_);
    seconds[stage_] = s;
    if (!quiet_) std::fprintf(stderr, "lc2wf-reconstruct: %s: %s (%.2f s)\n", stage_.c_str(), detail.c_str(), s);
  }

 private:
  bool quiet_;
  std::string stage_;
  Clock::time_point t_;
};

// What a photo's EXIF says, read once for the focal length (images stage) and the GPS fix (frame stage).
struct PhotoExif {
  std::optional<ExifFocal> focal;
  std::optional<GpsFix> gps;
  std::string gps_why_not;
};

std::vector<PhotoExif> read_photo_exif(const ImageFolder& folder) {
  std::vector<PhotoExif> out(folder.paths.size());
  for (size_t i = 0; i < folder.paths.size(); ++i) {
    std::string head;
    try {
      head = exif::read_head(folder.paths[i]);
    } catch (const std::exception& e) {  // a photo that went away since it was decoded
      throw StageError("images", e.what());
    }
    out[i].focal = exif_focal(head, std::max(folder.sizes[i].width, folder.sizes[i].height));
    out[i].gps = exif_gps(head, &out[i].gps_why_not);
  }
  return out;
}

// Each photo's 35 mm-equivalent focal length: --intrinsics' fx or --focal-35mm, else its EXIF, else the default;
// in words, where they came from; and whether any is the default, a guess.
std::vector<double> photo_focals(const ReconstructOptions& o, const ImageFolder& folder, const std::vector<PhotoExif>& photo_exif,
                                 std::string& source, bool& guessed) {
  std::vector<double> out;
  int from_exif = 0;
  for (size_t i = 0; i < folder.paths.size(); ++i) {
    const int longer_side = std::max(folder.sizes[i].width, folder.sizes[i].height);
    const std::optional<ExifFocal>& exif = photo_exif[i].focal;
    from_exif += exif.has_value();
    out.push_back(o.intrinsics   ? (*o.intrinsics)(0) * 36.0 / longer_side
                  : o.focal_35mm ? *o.focal_35mm
                  : exif         ? exif->focal_35mm
                                 : ReconstructOptions::kDefaultFocal35mm);
  }
  guessed = !o.intrinsics && !o.focal_35mm && from_exif < static_cast<int>(out.size());
  const std::string fallback = "the default";
  source = o.intrinsics   ? "--intrinsics"
           : o.focal_35mm ? "--focal-35mm"
           : from_exif == static_cast<int>(out.size()) ? "EXIF"
           : from_exif == 0 ? fallback
                            : "EXIF (" + std::to_string(from_exif) + " of " + std::to_string(out.size()) + " photos), " + fallback + " for the others";
  return out;
}

// One K per photo: --intrinsics (photos of one size only: a sideways photo's K is the upright one turned, which
// way unknown), else the 35 mm-equivalent focal length over the longer side (film's 36 mm side) and the centre.
std::vector<Eigen::Matrix3d> colmap_intrinsics(const ReconstructOptions& o, const std::vector<cv::Size>& sizes,
                                               const std::vector<double>& focal_35mm) {
  std::vector<Eigen::Matrix3d> out;
  for (size_t i = 0; i < sizes.size(); ++i) {
    const cv::Size& size = sizes[i];
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    if (o.intrinsics) {
      if (size != sizes.front())
        throw StageError("cameras", "--intrinsics gives one camera, but the photos have several sizes (" + describe_sizes(sizes) +
                                        "): give photos of one size, or leave --intrinsics out (--focal-35mm then sets each size's focal length)");
      const Eigen::Vector4d& p = *o.intrinsics;
      K << p(0), 0, p(2), 0, p(1), p(3), 0, 0, 1;
    } else {
      const double f = focal_35mm[i] / 36.0 * std::max(size.width, size.height);
      K << f, 0, (size.width - 1) / 2.0, 0, f, (size.height - 1) / 2.0, 0, 0, 1;
    }
    out.push_back(K);
  }
  return out;
}

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json similarity_json(const Similarity& s) {
  Json R = Json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R.push_back(s.R(r, c));
  return {{"scale", s.scale}, {"R", R}, {"t", vec_json(s.t)}};
}

// The view index of an image file name among the registered views, or a StageError naming it.
int registered_view_of(const std::string& name, const std::vector<fs::path>& paths, const std::vector<int>& image_of_view) {
  for (size_t v = 0; v < image_of_view.size(); ++v)
    if (paths[image_of_view[v]].filename() == name) return static_cast<int>(v);
  throw StageError("frame", "--known-distance image '" + name + "' is not a registered image");
}

struct GpsAlignment {
  std::optional<Similarity> to_enu;  // camera centres -> local east-north-up metres
  Json report;
};

// The registered photos' EXIF GPS fixes and the similarity that puts their camera centres onto them; no
// similarity (and the reason in the report) with fewer than `min_photos` fixes or fixes on one line.
GpsAlignment align_to_gps(const std::vector<Camera>& registered, const std::vector<int>& image_of_view,
                          const std::vector<PhotoExif>& photo_exif, int min_photos, const SimilarityFitOptions& fit_options,
                          double max_residual_share) {
  GpsAlignment a;
  std::vector<GpsFix> fixes;
  std::vector<Vec3> centres;
  std::map<std::string, int> why_not;
  for (size_t v = 0; v < registered.size(); ++v) {
    std::optional<GpsFix> fix = photo_exif[image_of_view[v]].gps;
    std::string why = photo_exif[image_of_view[v]].gps_why_not;
    if (fix && !fix->has_altitude) fix.reset(), why = "GPS without altitude";
    if (!fix) {
      ++why_not[why];
      continue;
    }
    fixes.push_back(*fix);
    centres.push_back(registered[v].center());
  }
  a.report = {{"used", false}, {"photos_with_gps", fixes.size()}, {"photos_without", why_not}};
  if (static_cast<int>(fixes.size()) < min_photos) {
    a.report["why_not"] = std::to_string(fixes.size()) + " registered photo(s) with GPS and altitude, " + std::to_string(min_photos) + " needed";
    return a;
  }
  try {
    const SimilarityFit fit = fit_similarity(centres, local_enu(fixes), fit_options);
    const double spread = fit.dst_spread;
    a.report["inliers"] = fit.inliers.size();
    a.report["rms_residual_m"] = fit.rms_residual;
    a.report["median_residual_m"] = fit.median_residual;
    a.report["spread_m"] = spread;
    if (fit.rms_residual > max_residual_share * spread) {
      a.report["why_not"] = "the camera centres fit the GPS fixes to " + format_number("%.1f", fit.rms_residual) + " m RMS, " +
                            format_number("%.0f", 100 * fit.rms_residual / spread) + " % of their " + format_number("%.1f", spread) +
                            " m spread (more than " + format_number("%.0f", 100 * max_residual_share) + " %): too noisy for scale and up";
      return a;
    }
    a.to_enu = fit.transform;
    a.report["used"] = true;
  } catch (const std::invalid_argument& e) {
    a.report["why_not"] = e.what();
  }
  return a;
}

double search_ratio(const ScaleSearchResult& s) { return s.runner_up_score > 0 ? s.best_score / s.runner_up_score : 0.0; }

Json scale_search_json(const ScaleSearchResult& s, const ScaleSearchOptions& o) {
  Json curve = Json::array();
  for (const ScaleCandidate& c : s.curve) curve.push_back({{"height_m", c.height_m}, {"score", c.score}, {"junctions", c.junctions}, {"edges", c.edges}});
  return {{"measure", to_string(o.measure)}, {"height_m", s.height_m}, {"score", s.best_score}, {"runner_up_height_m", s.runner_up_height_m},
          {"runner_up_score", s.runner_up_score}, {"best_over_runner_up", search_ratio(s)}, {"curve", curve}};
}

}  // namespace

namespace {

// One run of the pipeline: each stage a method that reads what the stages before it left and records its
// part of the report, in the order reconstruct() calls them.
class ReconstructRun {
 public:
  explicit ReconstructRun(const ReconstructOptions& o) : o_(o), ws_(o.workspace, o.keep), log_(o.quiet) {
    report_ = {{"format", "lc2wf-reconstruct-report"}, {"version", 1}, {"images_dir", o.images.string()}};
    add_version_fields(report_);
  }

  void load_weights() {
    log_.start("weights");
    try {
      predictor_.emplace(o_.weights);
      height_model_ = choose_height_model(o_.height_model, o_.weights);
    } catch (const std::exception& e) {
      throw StageError("weights", e.what());
    }
    log_.done(seconds_, o_.weights.string());
  }

  void read_images() {
    log_.start("images");
    folder_ = read_image_folder(o_.images, o_.min_images);
    for (const auto& n : folder_.unreadable) result_.warnings.push_back("unreadable image skipped: " + n);
    if (!folder_.unsupported.empty()) result_.warnings.push_back(unsupported_text(folder_.unsupported));
    Json sizes = Json::array();
    for (const cv::Size& size : folder_.sizes) sizes.push_back(Json::array({size.width, size.height}));
    report_["images"] = {{"read", folder_.images.size()}, {"unreadable", folder_.unreadable}, {"not_read", folder_.unsupported}, {"sizes", sizes}};
    photo_exif_ = read_photo_exif(folder_);
    std::string focal_text;
    if (o_.cameras.empty()) {  // the focal lengths COLMAP starts from (known cameras bring their own)
      std::string focal_source;
      focal_35mm_ = photo_focals(o_, folder_, photo_exif_, focal_source, focal_guessed_);
      report_["images"]["focal_35mm"] = focal_35mm_;
      report_["images"]["focal_source"] = focal_source;
      const auto [f_min, f_max] = std::minmax_element(focal_35mm_.begin(), focal_35mm_.end());
      focal_text = ", focal length " + format_number("%g", *f_min) + (*f_min == *f_max ? "" : "-" + format_number("%g", *f_max)) +
                   " mm (35 mm equivalent) from " + focal_source + (focal_guessed_ ? " (a guess for COLMAP to refine)" : "");
    }
    log_.done(seconds_, std::to_string(folder_.images.size()) + " image(s): " + describe_sizes(folder_.sizes) +
                            focal_text + (folder_.unreadable.empty() ? "" : ", " + std::to_string(folder_.unreadable.size()) + " unreadable"));
  }

  void register_cameras() {
    log_.start("cameras");
    ColmapOptions colmap = o_.colmap;
    if (o_.threads > 0) colmap.threads = o_.threads;
    colmap.refine_focal_length = focal_guessed_;
    cams_ = o_.cameras.empty()
                ? cameras_from_colmap(folder_.paths, colmap_intrinsics(o_, folder_.sizes, focal_35mm_), ws_.root() / "colmap", colmap)
                : cameras_from_file(o_.cameras, folder_.all_names, folder_.paths);
    Json unregistered = Json::array();
    for (size_t i = 0; i < cams_.cameras.size(); ++i) {
      if (cams_.cameras[i]) image_of_view_.push_back(static_cast<int>(i));
      else unregistered.push_back(folder_.paths[i].filename().string());
    }
    Json steps = Json::object();
    for (const auto& [step, s] : cams_.step_seconds) steps[step] = steps.value(step, 0.0) + s;  // the mapper may run twice
    report_["cameras"] = {{"source", cams_.source}, {"registered", image_of_view_.size()}, {"unregistered", unregistered}, {"colmap_seconds", steps}};
    if (o_.cameras.empty()) {  // the focal lengths COLMAP ended with (refined where they were guessed), 35 mm equivalent
      Json focal = Json::array();
      for (const auto& c : cams_.cameras) focal.push_back(c ? Json(c->K(0, 0) * 36.0 / std::max(c->width, c->height)) : Json(nullptr));
      report_["cameras"]["focal_refined"] = cams_.focal_refined;
      report_["cameras"]["focal_35mm"] = focal;
    }
    if (static_cast<int>(image_of_view_.size()) < o_.min_images)
      throw StageError("cameras", std::to_string(image_of_view_.size()) + " of " + std::to_string(folder_.paths.size()) +
                                      " images registered (" + cams_.source + (o_.cameras.empty() ? "" : " " + o_.cameras.string()) +
                                      "), at least " + std::to_string(o_.min_images) + " needed; unregistered: " + json_text(unregistered) +
                                      (o_.cameras.empty() ? "; COLMAP log: " + (ws_.root() / "colmap" / "colmap.log").string() : ""));
    if (!unregistered.empty()) result_.warnings.push_back(std::to_string(unregistered.size()) + " image(s) not registered: " + json_text(unregistered));
    const std::string focal = !focal_guessed_ ? "" : cams_.focal_refined ? ", focal lengths refined" : ", focal lengths kept (no model with them free)";
    log_.done(seconds_, std::to_string(image_of_view_.size()) + "/" + std::to_string(folder_.paths.size()) + " registered (" + cams_.source + ")" + focal);
  }

  // Where the poses came from, for errors that bad poses cause downstream (a wrong model, not a wrong flag).
  std::string pose_origin() const {
    return o_.cameras.empty() ? "COLMAP's model in " + (ws_.root() / "colmap").string() : o_.cameras.string();
  }

  void detect_lines() {
    log_.start("lsd");
    views_.resize(image_of_view_.size());
    long long segments_2d = 0;
    for (size_t v = 0; v < views_.size(); ++v) {
      views_[v].camera = *cams_.cameras[image_of_view_[v]];
      views_[v].segments = detect_segments(folder_.images[image_of_view_[v]], o_.lsd);
      segments_2d += static_cast<long long>(views_[v].segments.size());
    }
    report_["segments_2d"] = segments_2d;
    if (segments_2d == 0)
      throw StageError("lsd", "no 2D line segment in any of the " + std::to_string(views_.size()) + " registered images of " + o_.images.string());
    log_.done(seconds_, std::to_string(segments_2d) + " 2D segments");
  }

  void triangulate() {
    log_.start("triangulation");
    TriangulationStats tstats;
    lines_ = triangulate_lines(views_, o_.triangulator, std::nullopt, &tstats);
    report_["lines_3d"] = lines_.size();
    report_["lines_3d_from_endpoints"] = tstats.kept_by_endpoints;  // lines along the cameras' path (tools/README.md)
    if (lines_.empty())
      throw StageError("triangulation", "no 3D line from " + std::to_string(report_["segments_2d"].get<long long>()) + " 2D segments in " +
                                            std::to_string(views_.size()) + " views (too little overlap between the images, or poses too inaccurate: " + pose_origin() + ")");
    log_.done(seconds_, std::to_string(lines_.size()) + " 3D lines");
  }

  // Up, ground and scale: from the given scale, a known distance, GPS, a building height, the storeys or the scale search.
  void estimate_frame() {
    log_.start("frame");
    for (const auto& v : views_) registered_.push_back(v.camera);
    int min_supports = 0;
    const std::vector<Segment3> segments = frame_lines(min_supports);
    MetricFrameOptions fo = o_.frame;
    fo.height_model = height_model_;
    if (cams_.metric_z_up && !o_.up_given) fo.up = UpSource::kInputZ;  // the project's cameras are metric and z-up
    if (cams_.metric_z_up && !o_.scale_given) fo.scale = 1.0;
    if (fo.known_distance_m > 0) {
      fo.known_view_a = registered_view_of(o_.known_image_a, folder_.paths, image_of_view_);
      fo.known_view_b = registered_view_of(o_.known_image_b, folder_.paths, image_of_view_);
    }
    Json gps_report = {{"used", false}};
    if (o_.use_gps && !cams_.metric_z_up && fo.scale == 0 && fo.known_distance_m == 0) {
      const GpsAlignment gps = align_to_gps(registered_, image_of_view_, photo_exif_, o_.min_gps_photos, o_.gps_fit, o_.max_gps_residual_share);
      gps_report = gps.report;
      if (gps.to_enu) fo.gps_to_enu = gps.to_enu;
    }
    try {
      std::vector<Segment3> all_lines;
      for (const auto& l : lines_) all_lines.push_back(l.line);
      frame_ = estimate_metric_frame(registered_, segments, fo, &all_lines);
    } catch (const std::invalid_argument& e) {
      throw StageError("frame", e.what());
    }
    if (frame_.needs_scale_search) {
      log_.done(seconds_, "up from " + frame_.up_source + ", scale left to the search (no GPS, known distance, building height, storeys (" +
                              frame_.storeys.why_not + ") or height model" +
                              (frame_.line_height_why_not.empty() ? std::string() : " (" + frame_.line_height_why_not + ")") + ")");
      log_.start("scale search");
      // Each candidate height sees what inference would: the cloud confirmed in metres at that height.
      search_ = search_scale(
          *predictor_, [&](double h) { return keep_confirmed_lines(cloud_in(frame_.scaled_by(h)), o_.confirmation); }, o_.post,
          o_.scale_search);
      frame_ = frame_.scaled_by(search_->height_m);
    }
    cloud_ = cloud_in(frame_);
    for (const Segment3& s : cloud_.segments)
      if (!within_coordinate_limit(s.a) || !within_coordinate_limit(s.b))  // e.g. --scale 1e20
        throw StageError("frame", "the scale " + std::to_string(frame_.to_metric.scale) + " m/unit (" +
                                      (frame_.scale_source == "given" ? std::string("--scale") :
                                       frame_.scale_source == "known distance" ? std::string("--known-distance") : frame_.scale_source) +
                                      ") puts the cloud beyond +-1e9 m");
    report_["frame"] = {{"to_metric", similarity_json(frame_.to_metric)}, {"up_input", vec_json(frame_.up_input)},
                        {"up_source", frame_.up_source}, {"vertical_lines", frame_.vertical_lines},
                        {"scale_source", frame_.scale_source}, {"height_input_units", frame_.height_input},
                        {"lines_used", segments.size()}, {"lines_min_supports", std::max(min_supports, 0)},
                        {"height_m", frame_.height_input * frame_.to_metric.scale}, {"gps", gps_report}};
    if (search_) report_["frame"]["scale_search"] = scale_search_json(*search_, o_.scale_search);
    if (storeys_consulted(frame_)) {
      report_["frame"]["storeys"] = storey_scale_json(frame_.storeys, fo.storeys);
      if (height_model_) report_["frame"]["line_statistics"] = line_height_json(frame_, *height_model_);
    }
    log_.done(seconds_, search_ ? "building height " + format_number("%.1f", search_->height_m) + " m (" +
                                      format_number("%.2f", search_ratio(*search_)) + "x the runner-up's score at " +
                                      format_number("%.1f", search_->runner_up_height_m) + " m), " +
                                      std::to_string(search_->curve.size()) + " heights tried"
                                : "up from " + frame_.up_source + ", scale " + std::to_string(frame_.to_metric.scale) + " m/unit (" +
                                      frame_.scale_source + ")" +
                                      (frame_.scale_source == "gps"
                                           ? ", GPS residual " + format_number("%.2f", gps_report.value("rms_residual_m", 0.0)) + " m"
                                       : frame_.scale_source == "storeys"
                                           ? ", " + format_number("%.1f", frame_.storeys.storeys) + " storeys of " +
                                                 format_number("%.1f", fo.storeys.storey_height_m) + " m, +-" +
                                                 format_number("%.0f", 100 * fo.storeys.storey_uncertainty) + " %"
                                       : frame_.scale_source == "line statistics" ? ", " + line_height_text(frame_, *height_model_)
                                           : ""));
  }

  void confirm_lines() {
    log_.start("confirmation");
    const size_t triangulated = cloud_.segments.size();
    cloud_ = keep_confirmed_lines(cloud_, o_.confirmation);  // in metres: the overlap test's 10 cm needs the frame
    report_["lines_unconfirmed"] = triangulated - cloud_.segments.size();
    if (cloud_.segments.empty())
      throw StageError("confirmation", "none of the " + std::to_string(triangulated) + " 3D lines is overlapped by a line of " +
                                           std::to_string(o_.confirmation.min_other_views) +
                                           " other view(s) (--min-confirming-views; 0 keeps every line; poses: " + pose_origin() + ")");
    log_.done(seconds_, std::to_string(cloud_.segments.size()) + " of " + std::to_string(triangulated) + " lines confirmed by another view");
  }

  void infer() {
    log_.start("inference");
    inference_ = search_ ? search_->inference : predictor_->predict(cloud_, o_.post);  // the search ran it already
    const Wireframe& w = inference_.wireframe.wireframe;
    report_["junctions"] = w.junctions.size();
    report_["edges"] = w.edges.size();
    report_["notes"] = inference_.notes;
    if (w.edges.empty()) result_.warnings.push_back("empty wireframe: " + Json(inference_.notes).dump());
    log_.done(seconds_, std::to_string(w.junctions.size()) + " junctions, " + std::to_string(w.edges.size()) + " edges");
    // Photos from the street see one or two sides: say which, so the wireframe is not taken for the whole.
    const CameraCoverage coverage = camera_coverage(cloud_.cameras, w, cloud_.segments);
    report_["coverage"] = coverage_json(coverage);
    if (!o_.quiet) std::fprintf(stderr, "lc2wf-reconstruct: coverage: %s\n", coverage.summary().c_str());
  }

  ReconstructResult write_outputs(Clock::time_point t_total) {
    log_.start("outputs");
    const fs::path stage = ws_.staging();
    write_line_cloud(stage / "cloud.lcloud", cloud_);
    write_line_obj(stage / "cloud.obj", cloud_);
    write_prediction(stage, "wireframe", inference_.wireframe, inference_.notes);
    if (o_.surfaces) {
      const SurfaceModel surfaces = surfaces_from_wireframe(inference_.wireframe.wireframe, inference_.wireframe.edge_scores);
      write_surface_outputs(stage, "wireframe", surfaces);
      report_["surfaces"] = {{"status", to_string(surfaces.status)}, {"faces", surfaces.faces.size()}, {"reasons", surfaces.reasons}};
    }
    write_preview(stage / "preview.png", cloud_, inference_.wireframe.wireframe, nullptr);
    Json cameras_out = Json::array();
    for (size_t i = 0, v = 0; i < cams_.cameras.size(); ++i)
      cameras_out.push_back(cams_.cameras[i] ? camera_to_json(cloud_.cameras[v++]) : Json(nullptr));
    write_file_atomic(stage / "cameras.json", cameras_out.dump());
    if (!o_.reference_cameras.empty()) align_to_reference_cameras(stage);
    log_.done(seconds_, "staged in " + stage.string());
    seconds_["total"] = seconds_since(t_total);
    report_["seconds"] = seconds_;
    result_.exit_code = result_.warnings.empty() ? kExitDone : kExitPartly;
    report_["warnings"] = result_.warnings;
    report_["exit_code"] = result_.exit_code;
    write_file_atomic(stage / "report.json", json_text(report_, 2));
    result_.written = ws_.publish(o_.out);
    if (!ws_.removed_at_exit()) result_.workspace = ws_.root().string();
    if (!o_.quiet)
      std::fprintf(stderr, "lc2wf-reconstruct: wrote %zu files to %s (%.1f s in total)%s\n", result_.written.size(), o_.out.string().c_str(),
                   seconds_["total"].get<double>(), result_.workspace.empty() ? "" : (", workspace kept: " + result_.workspace).c_str());
    result_.report = report_;
    return result_;
  }

 private:
  // The best-supported lines only: texture clutter (most of a cloud from photo-like textures, with lines
  // metres above the roof and below the ground) would bias the height, the up and the origin. Support counts
  // grow with the number of views, so the threshold is the largest that keeps enough lines.
  std::vector<Segment3> frame_lines(int& min_supports) const {
    std::vector<Segment3> segments;
    for (min_supports = o_.frame_max_supports; min_supports >= 3; --min_supports) {
      segments.clear();
      for (const auto& l : lines_)
        if (static_cast<int>(l.support.size()) >= min_supports) segments.push_back(l.line);
      if (static_cast<int>(segments.size()) >= o_.frame_min_lines) return segments;
    }
    segments.clear();
    for (const auto& l : lines_) segments.push_back(l.line);
    return segments;
  }

  // The cloud in a frame: cameras, lines and their supports.
  LineCloud cloud_in(const MetricFrame& f) const {
    LineCloud c;
    c.name = "cloud";
    for (const Camera& cam : registered_) c.cameras.push_back(f.to_metric.apply(cam));
    for (const TriangulatedLine& l : lines_) {
      c.segments.push_back(f.to_metric.apply(l.line));
      std::vector<Observation> obs;
      for (const SupportingSegment& s : l.support) obs.push_back({s.ref.view, views_[s.ref.view].segments[s.ref.segment]});
      c.support.push_back(std::move(obs));
    }
    return c;
  }

  // Evaluation only: the similarity that puts our cameras onto known ones, applied to the wireframe.
  void align_to_reference_cameras(const fs::path& stage) {
    std::vector<Camera> reference;
    const std::string source = o_.reference_cameras.string();
    Json list;
    try {
      list = Json::parse(read_file(o_.reference_cameras));
    } catch (const Json::exception& e) {
      throw StageError("outputs", source + ": not JSON: " + e.what());
    }
    if (!list.is_array()) throw StageError("outputs", source + ": expected an array of cameras, one per image");
    for (size_t i = 0; i < list.size(); ++i) reference.push_back(camera_from_json(list[i], source + " entry " + std::to_string(i)));
    if (reference.size() != cams_.cameras.size())
      throw StageError("outputs", source + " has " + std::to_string(reference.size()) + " cameras for " +
                                      std::to_string(cams_.cameras.size()) + " images");
    std::vector<std::optional<Camera>> ours(cams_.cameras.size());
    for (size_t v = 0; v < image_of_view_.size(); ++v) ours[image_of_view_[v]] = cloud_.cameras[v];
    AlignOptions align;
    align.outlier_factor = 3;
    const PoseComparison pc = align_to_reference(reference, ours, align);
    ScoredWireframe aligned = inference_.wireframe;
    for (Vec3& j : aligned.wireframe.junctions) j = pc.scale * pc.rotation * j + pc.translation;
    write_prediction(stage, "wireframe_aligned", aligned, inference_.notes);
    Similarity to_reference;
    to_reference.scale = pc.scale, to_reference.R = pc.rotation, to_reference.t = pc.translation;
    report_["reference"] = {{"cameras", source},   {"scale_to_reference", pc.scale},
                            {"to_reference", similarity_json(to_reference)},
                            {"aligned_on", pc.inliers},                   {"rotation_error_deg_median", pc.median_rotation_deg},
                            {"centre_error_median", pc.median_centre_error}, {"camera_distance", pc.camera_distance}};
  }

  const ReconstructOptions& o_;
  Workspace ws_;
  StageLog log_;
  ReconstructResult result_;
  Json report_;
  Json seconds_ = Json::object();
  std::optional<WireframePredictor> predictor_;
  std::optional<HeightModel> height_model_;
  ImageFolder folder_;
  std::vector<PhotoExif> photo_exif_;  // per readable photo
  std::vector<double> focal_35mm_;     // per readable photo (used when COLMAP estimates the cameras)
  bool focal_guessed_ = false;      // some photo's focal length is the default: COLMAP refines it
  CameraSet cams_;
  std::vector<int> image_of_view_;  // registered images only
  std::vector<TriangulationView> views_;
  std::vector<TriangulatedLine> lines_;
  std::vector<Camera> registered_;
  MetricFrame frame_;
  std::optional<ScaleSearchResult> search_;
  LineCloud cloud_;
  InferenceResult inference_;
};

}  // namespace

ReconstructResult reconstruct(const ReconstructOptions& o) {
  o.Check();
  const auto t_total = Clock::now();
  set_num_threads(o.threads);
  if (o.threads > 0) omp_set_num_threads(o.threads);
  ReconstructRun run(o);
  run.load_weights();
  run.read_images();
  run.register_cameras();
  run.detect_lines();
  run.triangulate();
  run.estimate_frame();
  run.confirm_lines();
  run.infer();
  return run.write_outputs(t_total);
}

}  // namespace lc2wf
