// lc2wf-colmap-poses: camera poses for a folder of images with COLMAP 3.8 (CPU), written in our camera
// format; when the folder has reference cameras (cameras.json from lc2wf-dataset --keep-views), the
// result is aligned to them and the pose errors are reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/util/cli.h"
#include "core/util/version_json.h"
#include "core/util/workspace.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "tools/colmap/colmap_poses.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using lc2wf::UsageError;

namespace {

constexpr const char* kUsage = R"(Usage: lc2wf-colmap-poses IMAGES_DIR [-o OUT] [options]

Runs COLMAP's SIFT (CPU), our exact descriptor matching, COLMAP's geometric verification and mapper on the images of IMAGES_DIR
(*.png, *.jpg, in name order) with fixed pinhole intrinsics and writes their cameras (K, R, t per image in
the OpenCV convention, null for unregistered images). Intrinsics come from --intrinsics (one camera) or
IMAGES_DIR/cameras.json (each image its own); with IMAGES_DIR/cameras.json the poses are aligned to those cameras (similarity)
and the errors go into the report (per view and median/max, centre errors also relative to the camera
distance), together with the wall time of each COLMAP step. The report (JSON) goes to stdout.
COLMAP works in a private temporary folder, removed at the end (kept, and named, when COLMAP fails).

options:
  -o, --out OUT               cameras JSON to write (default IMAGES_DIR/cameras_colmap.json)
  --intrinsics fx,fy,cx,cy    OpenCV pixel convention (centre of the top-left pixel = 0,0)
  --workspace DIR             COLMAP's folder instead of a private one: it must be new, empty or one an
                              earlier run made (it holds .lc2wf-workspace); it is never deleted
  --keep                      keep the private workspace (its path is printed)
  --colmap PATH               COLMAP executable (default colmap)
  --matcher exhaustive|sequential
                              all image pairs (default) or only views close in name order
  --overlap N                 sequential matcher: next views matched per view (default 10)
  --max-features N            SIFT features per image (default 4000)
  --first-octave N            SIFT's first octave: -1 the image doubled first, 0 at its own size (fewer,
                              larger features found in less time); default -1 for images of at most 1600
                              pixels on their longer side, 0 for larger ones (SIFT scales them down first)
  --init-min-inliers N        mapper: verified matches of the initial pair (default 100)
  --abs-pose-min-inliers N    mapper: 2D-3D inliers to register a view (default 30)
  --outlier-factor F          alignment: leave views whose centre error exceeds F x the median out of
                              the similarity fit (e.g. 3; default 0 = fit all registered views)
  -j, --threads N             threads of every COLMAP step (default: all cores)
  -q, --quiet                 no summary line on stderr
Exit code 1: done, but some images were skipped (an entry named *.png/*.jpg that is not a regular file) or
not registered; each is named on stderr, also with -q. 3: fewer than 3 images, COLMAP failed (its log is
named), or an I/O error.
)";

struct Args {
  fs::path views, workspace, out;
  bool keep = false, quiet = false;
  std::optional<Eigen::Vector4d> intrinsics;
  lc2wf::ColmapOptions colmap;
  lc2wf::AlignOptions align;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return lc2wf::flag_value(argc, argv, i); };
    if (f == "-o" || f == "--out") a.out = value();
    else if (f == "--workspace") a.workspace = value();
    else if (f == "--keep") a.keep = true;
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "--intrinsics") {
      const std::string v = value();
      double fx, fy, cx, cy;
      char tail;
      if (std::sscanf(v.c_str(), "%lf,%lf,%lf,%lf%c", &fx, &fy, &cx, &cy, &tail) != 4)
        throw UsageError("--intrinsics expects fx,fy,cx,cy, got '" + v + "'");
      a.intrinsics = Eigen::Vector4d(fx, fy, cx, cy);
    } else if (f == "--colmap") a.colmap.executable = value();
    else if (f == "--matcher") a.colmap.matcher = value();
    else if (f == "--overlap") a.colmap.sequential_overlap = lc2wf::int_flag(f, value());
    else if (f == "--max-features") a.colmap.max_features = lc2wf::int_flag(f, value());
    else if (f == "--first-octave") a.colmap.first_octave = lc2wf::int_flag(f, value());
    else if (f == "--init-min-inliers") a.colmap.init_min_inliers = lc2wf::int_flag(f, value());
    else if (f == "--abs-pose-min-inliers") a.colmap.abs_pose_min_inliers = lc2wf::int_flag(f, value());
    else if (f == "--outlier-factor") a.align.outlier_factor = lc2wf::number_flag(f, value());
    else if (f == "-j" || f == "--threads") a.colmap.threads = lc2wf::threads_flag(f, value());
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option '" + f + "'");
    else if (a.views.empty()) a.views = f;
    else throw UsageError("one image folder only, got '" + f + "' too");
  }
  if (a.views.empty()) throw UsageError("IMAGES_DIR is required");
  lc2wf::check_options([&] { a.colmap.Check(); a.align.Check(); },
                       {{"ColmapOptions.executable", "--colmap"}, {"ColmapOptions.max_features", "--max-features"},
                        {"ColmapOptions.first_octave", "--first-octave"}, {"ColmapOptions.matcher", "--matcher"},
                        {"ColmapOptions.sequential_overlap", "--overlap"},
                        {"ColmapOptions.init_min_inliers", "--init-min-inliers"},
                        {"ColmapOptions.abs_pose_min_inliers", "--abs-pose-min-inliers"},
                        {"AlignOptions.outlier_factor", "--outlier-factor"}});
  // Inputs next (data errors, exit 3), before anything is written.
  if (!fs::is_directory(a.views)) throw std::runtime_error("'" + a.views.string() + "' is not a folder");
  if (!a.intrinsics && !fs::exists(a.views / "cameras.json"))
    throw UsageError("no intrinsics: pass --intrinsics or provide IMAGES_DIR/cameras.json");
  if (a.out.empty()) a.out = a.views / "cameras_colmap.json";
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
  std::vector<fs::path> images, skipped;
  for (const auto& e : fs::directory_iterator(a.views)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") (e.is_regular_file() ? images : skipped).push_back(e.path());
  }
  std::sort(images.begin(), images.end());
  std::sort(skipped.begin(), skipped.end());
  // A folder or FIFO under an image's name is left out, and said so (also with -q).
  for (const fs::path& p : skipped) std::fprintf(stderr, "lc2wf-colmap-poses: skipped %s: not a regular file\n", p.string().c_str());
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
  // Each image's own intrinsics from cameras.json (images of several sizes are several COLMAP cameras), or the
  // one --intrinsics for all.
  std::vector<Eigen::Matrix3d> K;
  for (size_t i = 0; i < images.size(); ++i) K.push_back(reference.empty() ? Eigen::Matrix3d::Identity() : reference[i].K);
  if (a.intrinsics) {
    const Eigen::Vector4d& p = *a.intrinsics;
    for (Eigen::Matrix3d& k : K) k << p(0), 0, p(2), 0, p(1), p(3), 0, 0, 1;
  }
  lc2wf::Workspace workspace(a.workspace, a.keep);
  lc2wf::ColmapRun result;
  try {
    result = lc2wf::estimate_poses_with_colmap(images, K, workspace.root(), a.colmap);
  } catch (const std::exception& e) {
    workspace.keep();  // its colmap.log says why
    throw std::runtime_error(std::string(e.what()) + " (workspace kept: " + workspace.root().string() + ")");
  }
  auto& poses = result.cameras;
  Json report;
  report["images"] = images.size();
  report["registered"] = std::count_if(poses.begin(), poses.end(), [](const auto& p) { return p.has_value(); });
  Json seconds = Json::object();
  for (const auto& [step, s] : result.step_seconds) seconds[step] = s;
  report["seconds"] = seconds;
  if (!reference.empty()) report["comparison"] = comparison_report(lc2wf::align_to_reference(reference, poses, a.align));
  report["cameras"] = a.out.string();
  lc2wf::add_version_fields(report);
  Json out = Json::array();
  for (const auto& p : poses) out.push_back(p ? lc2wf::camera_to_json(*p) : Json(nullptr));
  lc2wf::write_file_atomic(a.out, out.dump());
  std::cout << report.dump(2) << std::endl;
  if (!a.quiet)
    std::fprintf(stderr, "lc2wf-colmap-poses: %d of %zu images registered -> %s%s\n", report["registered"].get<int>(), images.size(),
                 a.out.string().c_str(), workspace.removed_at_exit() ? "" : (" (workspace " + workspace.root().string() + ")").c_str());
  int unregistered = 0;
  for (size_t i = 0; i < poses.size() && i < images.size(); ++i)
    if (!poses[i]) {
      std::fprintf(stderr, "lc2wf-colmap-poses: not registered: %s (no pose found; null in %s)\n", images[i].string().c_str(),
                   a.out.string().c_str());
      ++unregistered;
    }
  return skipped.empty() && unregistered == 0 ? lc2wf::kExitDone : lc2wf::kExitPartly;
}

}  // namespace

int main(int argc, char** argv) { return lc2wf::cli_main({"lc2wf-colmap-poses", kUsage, {}}, argc, argv, parse_args, run); }
