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
#include "dataset/photo/exif_gps.h"
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

Eigen::Matrix3d colmap_intrinsics(const ReconstructOptions& o, int width, int height) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  if (o.intrinsics) {
    const Eigen::Vector4d& p = *o.intrinsics;
    K << p(0), 0, p(2), 0, p(1), p(3), 0, 0, 1;
  } else {
    const double f = o.focal_35mm / 36.0 * width;
    K << f, 0, (width - 1) / 2.0, 0, f, (height - 1) / 2.0, 0, 0, 1;
  }
  return K;
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
                          const std::vector<fs::path>& paths, int min_photos, const SimilarityFitOptions& fit_options) {
  GpsAlignment a;
  std::vector<GpsFix> fixes;
  std::vector<Vec3> centres;
  std::map<std::string, int> why_not;
  for (size_t v = 0; v < registered.size(); ++v) {
    std::string why;
    std::optional<GpsFix> fix;
    try {
      fix = exif_gps_of_file(paths[image_of_view[v]], &why);
    } catch (const std::exception& e) {
      why = e.what();
    }
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
    a.to_enu = fit.transform;
    a.report["used"] = true;
    a.report["inliers"] = fit.inliers.size();
    a.report["rms_residual_m"] = fit.rms_residual;
    a.report["median_residual_m"] = fit.median_residual;
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

ReconstructResult reconstruct(const ReconstructOptions& o) {
  o.Check();
  const auto t_total = Clock::now();
  set_num_threads(o.threads);
  if (o.threads > 0) omp_set_num_threads(o.threads);
  Workspace ws(o.workspace, o.keep);
  ReconstructResult result;
  Json& report = result.report;
  report = {{"format", "lc2wf-reconstruct-report"}, {"version", 1}, {"images_dir", o.images.string()}};
  add_version_fields(report);
  Json seconds = Json::object();
  StageLog log(o.quiet);

  log.start("weights");
  std::optional<WireframePredictor> predictor;
  try {
    predictor.emplace(o.weights);
  } catch (const std::exception& e) {
    throw StageError("weights", e.what());
  }
  log.done(seconds, o.weights.string());

  log.start("images");
  const ImageFolder folder = read_image_folder(o.images, o.min_images);
  for (const auto& n : folder.unreadable) result.warnings.push_back("unreadable image skipped: " + n);
  report["images"] = {{"read", folder.images.size()}, {"unreadable", folder.unreadable}, {"width", folder.width}, {"height", folder.height}};
  log.done(seconds, std::to_string(folder.images.size()) + " image(s) of " + std::to_string(folder.width) + "x" +
                        std::to_string(folder.height) + (folder.unreadable.empty() ? "" : ", " + std::to_string(folder.unreadable.size()) + " unreadable"));

  log.start("cameras");
  ColmapOptions colmap = o.colmap;
  if (o.threads > 0) colmap.threads = o.threads;
  const CameraSet cams = o.cameras.empty()
                             ? cameras_from_colmap(folder.paths, colmap_intrinsics(o, folder.width, folder.height), ws.root() / "colmap", colmap)
                             : cameras_from_file(o.cameras, folder.all_names, folder.paths);
  std::vector<int> image_of_view;  // registered images only
  Json unregistered = Json::array();
  for (size_t i = 0; i < cams.cameras.size(); ++i) {
    if (cams.cameras[i]) image_of_view.push_back(static_cast<int>(i));
    else unregistered.push_back(folder.paths[i].filename().string());
  }
  Json steps = Json::object();
  for (const auto& [step, s] : cams.step_seconds) steps[step] = s;
  report["cameras"] = {{"source", cams.source}, {"registered", image_of_view.size()}, {"unregistered", unregistered}, {"colmap_seconds", steps}};
  if (static_cast<int>(image_of_view.size()) < o.min_images)
    throw StageError("cameras", std::to_string(image_of_view.size()) + " of " + std::to_string(folder.paths.size()) +
                                    " images registered (" + cams.source + (o.cameras.empty() ? "" : " " + o.cameras.string()) + "), at least " + std::to_string(o.min_images) +
                                    " needed; unregistered: " + json_text(unregistered) +
                                    (o.cameras.empty() ? "; COLMAP log: " + (ws.root() / "colmap" / "colmap.log").string() : ""));
  if (!unregistered.empty()) result.warnings.push_back(std::to_string(unregistered.size()) + " image(s) not registered: " + json_text(unregistered));
  log.done(seconds, std::to_string(image_of_view.size()) + "/" + std::to_string(folder.paths.size()) + " registered (" + cams.source + ")");

  log.start("lsd");
  std::vector<TriangulationView> views(image_of_view.size());
  long long segments_2d = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    views[v].camera = *cams.cameras[image_of_view[v]];
    views[v].segments = detect_segments(folder.images[image_of_view[v]], o.lsd);
    segments_2d += static_cast<long long>(views[v].segments.size());
  }
  report["segments_2d"] = segments_2d;
  if (segments_2d == 0) throw StageError("lsd", "no 2D line segment in any of the " + std::to_string(views.size()) + " registered images of " + o.images.string());
  log.done(seconds, std::to_string(segments_2d) + " 2D segments");

  log.start("triangulation");
  TriangulationStats tstats;
  const std::vector<TriangulatedLine> lines = triangulate_lines(views, o.triangulator, std::nullopt, &tstats);
  report["lines_3d"] = lines.size();
  if (lines.empty())
    throw StageError("triangulation", "no 3D line from " + std::to_string(segments_2d) + " 2D segments in " + std::to_string(views.size()) +
                                          " views (too little overlap between the images, or poses too inaccurate)");
  log.done(seconds, std::to_string(lines.size()) + " 3D lines");

  log.start("frame");
  std::vector<Camera> registered;
  for (const auto& v : views) registered.push_back(v.camera);
  // The best-supported lines only: texture clutter (most of a cloud from photo-like textures, with
  // lines metres above the roof and below the ground) would bias the height, the up and the origin.
  // Support counts grow with the number of views, so the threshold is the largest that keeps enough lines.
  std::vector<Segment3> segments;
  int min_supports = o.frame_max_supports;
  for (; min_supports >= 3; --min_supports) {
    segments.clear();
    for (const auto& l : lines)
      if (static_cast<int>(l.support.size()) >= min_supports) segments.push_back(l.line);
    if (static_cast<int>(segments.size()) >= o.frame_min_lines) break;
  }
  if (min_supports < 3) {
    segments.clear();
    for (const auto& l : lines) segments.push_back(l.line);
  }
  MetricFrameOptions fo = o.frame;
  if (cams.metric_z_up && !o.up_given) fo.up = UpSource::kInputZ;  // the project's cameras are metric and z-up
  if (cams.metric_z_up && !o.scale_given) fo.scale = 1.0;
  if (fo.known_distance_m > 0) {
    fo.known_view_a = registered_view_of(o.known_image_a, folder.paths, image_of_view);
    fo.known_view_b = registered_view_of(o.known_image_b, folder.paths, image_of_view);
  }
  Json gps_report = {{"used", false}};
  if (o.use_gps && !cams.metric_z_up && fo.scale == 0 && fo.known_distance_m == 0) {
    const GpsAlignment gps = align_to_gps(registered, image_of_view, folder.paths, o.min_gps_photos, o.gps_fit);
    gps_report = gps.report;
    if (gps.to_enu) fo.gps_to_enu = gps.to_enu;
  }
  MetricFrame frame;
  try {
    frame = estimate_metric_frame(registered, segments, fo);
  } catch (const std::invalid_argument& e) {
    throw StageError("frame", e.what());
  }
  // The cloud in a frame: cameras, lines and their supports.
  auto cloud_in = [&](const MetricFrame& f) {
    LineCloud c;
    c.name = "cloud";
    for (const Camera& cam : registered) c.cameras.push_back(f.to_metric.apply(cam));
    for (const TriangulatedLine& l : lines) {
      c.segments.push_back(f.to_metric.apply(l.line));
      std::vector<Observation> obs;
      for (const SupportingSegment& s : l.support) obs.push_back({s.ref.view, views[s.ref.view].segments[s.ref.segment]});
      c.support.push_back(std::move(obs));
    }
    return c;
  };
  std::optional<ScaleSearchResult> search;
  if (frame.needs_scale_search) {
    log.done(seconds, "up from " + frame.up_source + ", scale left to the search (no GPS, known distance or building height)");
    log.start("scale search");
    // Each candidate height sees what inference would: the cloud confirmed in metres at that height.
    search = search_scale(
        *predictor, [&](double h) { return keep_confirmed_lines(cloud_in(frame.scaled_by(h)), o.confirmation); }, o.post, o.scale_search);
    frame = frame.scaled_by(search->height_m);
  }
  LineCloud cloud = cloud_in(frame);
  for (const Segment3& s : cloud.segments)
    if (!within_coordinate_limit(s.a) || !within_coordinate_limit(s.b))  // e.g. --scale 1e20
      throw StageError("frame", "the scale " + std::to_string(frame.to_metric.scale) + " m/unit (" +
                                    (frame.scale_source == "given" ? std::string("--scale") :
                                     frame.scale_source == "known distance" ? std::string("--known-distance") : frame.scale_source) +
                                    ") puts the cloud beyond +-1e9 m");
  report["frame"] = {{"to_metric", similarity_json(frame.to_metric)}, {"up_input", vec_json(frame.up_input)},
                     {"up_source", frame.up_source}, {"vertical_lines", frame.vertical_lines},
                     {"scale_source", frame.scale_source}, {"height_input_units", frame.height_input},
                     {"lines_used", segments.size()}, {"lines_min_supports", std::max(min_supports, 0)},
                     {"height_m", frame.height_input * frame.to_metric.scale}, {"gps", gps_report}};
  if (search) report["frame"]["scale_search"] = scale_search_json(*search, o.scale_search);
  log.done(seconds, search ? "building height " + format_number("%.1f", search->height_m) + " m (" + format_number("%.2f", search_ratio(*search)) +
                                 "x the runner-up's score at " + format_number("%.1f", search->runner_up_height_m) + " m), " +
                                 std::to_string(search->curve.size()) + " heights tried"
                           : "up from " + frame.up_source + ", scale " + std::to_string(frame.to_metric.scale) + " m/unit (" + frame.scale_source + ")" +
                                 (frame.scale_source == "gps" ? ", GPS residual " + format_number("%.2f", gps_report.value("rms_residual_m", 0.0)) + " m" : ""));

  log.start("confirmation");
  const size_t triangulated = cloud.segments.size();
  cloud = keep_confirmed_lines(cloud, o.confirmation);  // in metres: the overlap test's 10 cm needs the frame
  report["lines_unconfirmed"] = triangulated - cloud.segments.size();
  if (cloud.segments.empty())
    throw StageError("confirmation", "none of the " + std::to_string(triangulated) + " 3D lines is overlapped by a line of " +
                                         std::to_string(o.confirmation.min_other_views) +
                                         " other view(s) (--min-confirming-views; 0 keeps every line)");
  log.done(seconds, std::to_string(cloud.segments.size()) + " of " + std::to_string(triangulated) + " lines confirmed by another view");

  log.start("inference");
  const InferenceResult r = search ? search->inference : predictor->predict(cloud, o.post);  // the search ran it already
  report["junctions"] = r.wireframe.wireframe.junctions.size();
  report["edges"] = r.wireframe.wireframe.edges.size();
  report["notes"] = r.notes;
  if (r.wireframe.wireframe.edges.empty()) result.warnings.push_back("empty wireframe: " + Json(r.notes).dump());
  log.done(seconds, std::to_string(r.wireframe.wireframe.junctions.size()) + " junctions, " + std::to_string(r.wireframe.wireframe.edges.size()) + " edges");

  log.start("outputs");
  const fs::path stage = ws.staging();
  write_line_cloud(stage / "cloud.lcloud", cloud);
  write_line_obj(stage / "cloud.obj", cloud);
  write_prediction(stage, "wireframe", r.wireframe, r.notes);
  if (o.surfaces) {
    const SurfaceModel surfaces = surfaces_from_wireframe(r.wireframe.wireframe);
    write_surface_outputs(stage, "wireframe", surfaces);
    report["surfaces"] = {{"status", to_string(surfaces.status)}, {"faces", surfaces.faces.size()}, {"reasons", surfaces.reasons}};
  }
  write_preview(stage / "preview.png", cloud, r.wireframe.wireframe, nullptr);
  Json cameras_out = Json::array();
  for (size_t i = 0, v = 0; i < cams.cameras.size(); ++i)
    cameras_out.push_back(cams.cameras[i] ? camera_to_json(cloud.cameras[v++]) : Json(nullptr));
  write_file_atomic(stage / "cameras.json", cameras_out.dump());
  if (!o.reference_cameras.empty()) {
    // Evaluation only: the similarity that puts our cameras onto known ones, applied to the wireframe.
    std::vector<Camera> reference;
    const std::string source = o.reference_cameras.string();
    Json list;
    try {
      list = Json::parse(read_file(o.reference_cameras));
    } catch (const Json::exception& e) {
      throw StageError("outputs", source + ": not JSON: " + e.what());
    }
    if (!list.is_array()) throw StageError("outputs", source + ": expected an array of cameras, one per image");
    for (size_t i = 0; i < list.size(); ++i) reference.push_back(camera_from_json(list[i], source + " entry " + std::to_string(i)));
    if (reference.size() != cams.cameras.size())
      throw StageError("outputs", o.reference_cameras.string() + " has " + std::to_string(reference.size()) + " cameras for " +
                                      std::to_string(cams.cameras.size()) + " images");
    std::vector<std::optional<Camera>> ours(cams.cameras.size());
    for (size_t v = 0; v < image_of_view.size(); ++v) ours[image_of_view[v]] = cloud.cameras[v];
    AlignOptions align;
    align.outlier_factor = 3;
    const PoseComparison pc = align_to_reference(reference, ours, align);
    ScoredWireframe aligned = r.wireframe;
    for (Vec3& j : aligned.wireframe.junctions) j = pc.scale * pc.rotation * j + pc.translation;
    write_prediction(stage, "wireframe_aligned", aligned, r.notes);
    Similarity to_reference;
    to_reference.scale = pc.scale, to_reference.R = pc.rotation, to_reference.t = pc.translation;
    report["reference"] = {{"cameras", o.reference_cameras.string()},   {"scale_to_reference", pc.scale},
                           {"to_reference", similarity_json(to_reference)},
                           {"aligned_on", pc.inliers},                   {"rotation_error_deg_median", pc.median_rotation_deg},
                           {"centre_error_median", pc.median_centre_error}, {"camera_distance", pc.camera_distance}};
  }
  log.done(seconds, "staged in " + stage.string());
  seconds["total"] = seconds_since(t_total);
  report["seconds"] = seconds;
  result.exit_code = result.warnings.empty() ? kExitDone : kExitPartly;
  report["warnings"] = result.warnings;
  report["exit_code"] = result.exit_code;
  write_file_atomic(stage / "report.json", json_text(report, 2));
  result.written = ws.publish(o.out);
  if (!ws.removed_at_exit()) result.workspace = ws.root().string();
  if (!o.quiet)
    std::fprintf(stderr, "lc2wf-reconstruct: wrote %zu files to %s (%.1f s in total)%s\n", result.written.size(), o.out.string().c_str(),
                 seconds["total"].get<double>(), result.workspace.empty() ? "" : (", workspace kept: " + result.workspace).c_str());
  return result;
}

}  // namespace lc2wf
