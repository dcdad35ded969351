// lc2wf-colmap-poses: camera poses for a folder of images with COLMAP 3.8 (CPU), written in our camera
// format; when the folder has reference cameras (cameras.json from lc2wf-dataset --keep-views), the
// result is aligned to them and the pose errors are reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/util/cli.h"
#include "dataset/atomic_file.h"
#include "dataset/camera_json.h"
#include "tools/colmap/colmap_poses.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using lc2wf::UsageError;

namespace {

constexpr const char* kUsage = R"(usage: lc2wf-colmap-poses --views DIR [options]

Runs COLMAP (feature_extractor, exhaustive or sequential matcher, mapper; CPU) on the images of DIR
(*.png, *.jpg, in name order) with fixed pinhole intrinsics and writes DIR/cameras_colmap.json (K, R, t
per image in the OpenCV convention, null for unregistered images). Intrinsics come from --intrinsics or
DIR/cameras.json; with DIR/cameras.json the poses are aligned to those cameras (similarity) and the
errors are printed (per view and median/max, centre errors also relative to the camera distance),
together with the wall time of each COLMAP step.

options:
  --intrinsics fx,fy,cx,cy    OpenCV pixel convention (centre of the top-left pixel = 0,0)
  --workspace DIR             COLMAP working folder (default DIR/colmap)
  --colmap PATH               COLMAP executable (default colmap)
  --matcher exhaustive|sequential
                              all image pairs (default) or only views close in name order
  --overlap N                 sequential matcher: next views matched per view (default 10)
  --max-features N            SIFT features per image (default 4000)
  --init-min-inliers N        mapper: verified matches of the initial pair (default 100)
  --abs-pose-min-inliers N    mapper: 2D-3D inliers to register a view (default 30)
  --outlier-factor F          alignment: leave views whose centre error exceeds F x the median out of
                              the similarity fit (e.g. 3; default 0 = fit all registered views)
  --threads N                 threads of every COLMAP step (default: all cores)
  -h, --help                  this text

exit codes: 0 ok, 2 bad arguments, 3 COLMAP or I/O failure
)";

struct Args {
  fs::path views, workspace;
  std::string intrinsics;
  lc2wf::ColmapOptions colmap;
  lc2wf::AlignOptions align;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return lc2wf::flag_value(argc, argv, i); };
    if (f == "--views") a.views = value();
    else if (f == "--workspace") a.workspace = value();
    else if (f == "--intrinsics") a.intrinsics = value();
    else if (f == "--colmap") a.colmap.executable = value();
    else if (f == "--matcher") a.colmap.matcher = value();
    else if (f == "--overlap") a.colmap.sequential_overlap = lc2wf::int_flag(f, value());
    else if (f == "--max-features") a.colmap.max_features = lc2wf::int_flag(f, value());
    else if (f == "--init-min-inliers") a.colmap.init_min_inliers = lc2wf::int_flag(f, value());
    else if (f == "--abs-pose-min-inliers") a.colmap.abs_pose_min_inliers = lc2wf::int_flag(f, value());
    else if (f == "--outlier-factor") a.align.outlier_factor = lc2wf::number_flag(f, value());
    else if (f == "--threads") a.colmap.threads = lc2wf::int_flag(f, value());
    else throw UsageError("unknown argument '" + f + "'");
  }
  if (a.views.empty()) throw UsageError("--views DIR is required");
  if (!fs::is_directory(a.views)) throw UsageError("not a folder: " + a.views.string());
  if (a.workspace.empty()) a.workspace = a.views / "colmap";
  try {
    a.colmap.Check();
    a.align.Check();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (!a.intrinsics.empty()) {
    double fx, fy, cx, cy;
    if (std::sscanf(a.intrinsics.c_str(), "%lf,%lf,%lf,%lf", &fx, &fy, &cx, &cy) != 4) throw UsageError("--intrinsics expects fx,fy,cx,cy");
  } else if (!fs::exists(a.views / "cameras.json")) {
    throw UsageError("no intrinsics: pass --intrinsics or provide DIR/cameras.json");
  }
  return a;
}

// NaN (an unregistered view) becomes null in the report.
Json number_or_null(double x) { return std::isnan(x) ? Json(nullptr) : Json(x); }

Json comparison_report(const lc2wf::PoseComparison& pc) {
  Json r;
  r["aligned_on"] = pc.inliers;
  r["scale_to_reference"] = pc.scale;
  r["camera_distance"] = pc.camera_distance;
  r["centre_error"] = {{"median", pc.median_centre_error},
                       {"max", pc.max_centre_error},
                       {"median_relative", pc.median_centre_error / pc.camera_distance},
                       {"max_relative", pc.max_centre_error / pc.camera_distance}};
  r["rotation_error_deg"] = {{"median", pc.median_rotation_deg}, {"max", pc.max_rotation_deg}};
  Json per_view = Json::array();
  for (size_t i = 0; i < pc.centre_error.size(); ++i)
    per_view.push_back({{"centre_error", number_or_null(pc.centre_error[i])}, {"rotation_error_deg", number_or_null(pc.rotation_deg[i])}});
  r["per_view"] = per_view;
  return r;
}

int run(const Args& a) {
  try {
    std::vector<fs::path> images;
    for (const auto& e : fs::directory_iterator(a.views)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg")) images.push_back(e.path());
    }
    std::sort(images.begin(), images.end());
    if (images.size() < 3) throw std::runtime_error(a.views.string() + ": fewer than 3 images");
    std::vector<lc2wf::Camera> reference;
    const fs::path cameras = a.views / "cameras.json";
    if (fs::exists(cameras)) {
      Json list;
      try {
        list = Json::parse(lc2wf::read_file(cameras));
      } catch (const Json::exception& e) {  // e.g. "number overflow parsing '1e400'": name the file
        throw std::runtime_error(cameras.string() + ": not valid JSON: " + e.what());
      }
      for (const Json& j : list) reference.push_back(lc2wf::camera_from_json(j, cameras.string()));
      if (reference.size() != images.size())
        throw std::runtime_error(a.views.string() + ": cameras.json has " + std::to_string(reference.size()) + " cameras for " +
                                 std::to_string(images.size()) + " images");
    }
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    if (!a.intrinsics.empty()) {
      double fx, fy, cx, cy;
      std::sscanf(a.intrinsics.c_str(), "%lf,%lf,%lf,%lf", &fx, &fy, &cx, &cy);
      K << fx, 0, cx, 0, fy, cy, 0, 0, 1;
    } else {
      K = reference.front().K;
    }
    auto result = lc2wf::estimate_poses_with_colmap(images, K, a.workspace, a.colmap);
    auto& poses = result.cameras;
    Json report;
    report["images"] = images.size();
    report["registered"] = std::count_if(poses.begin(), poses.end(), [](const auto& p) { return p.has_value(); });
    Json seconds = Json::object();
    for (const auto& [step, s] : result.step_seconds) seconds[step] = s;
    report["seconds"] = seconds;
    if (!reference.empty()) report["comparison"] = comparison_report(lc2wf::align_to_reference(reference, poses, a.align));
    Json out = Json::array();
    for (const auto& p : poses) out.push_back(p ? lc2wf::camera_to_json(*p) : Json(nullptr));
    lc2wf::write_file_atomic(a.views / "cameras_colmap.json", out.dump());
    std::cout << report.dump(2) << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-colmap-poses: %s\n", e.what());
    return 3;
  }
}

}  // namespace

int main(int argc, char** argv) { return lc2wf::cli_main("lc2wf-colmap-poses", kUsage, argc, argv, parse_args, run); }
