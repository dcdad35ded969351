// lc2wf-colmap-poses: camera poses for a folder of images with COLMAP 3.8 (CPU), written in our camera
// format; when the folder has reference cameras (cameras.json from lc2wf-dataset --keep-views), the
// result is aligned to them and the pose errors are reported.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "dataset/atomic_file.h"
#include "dataset/camera_json.h"
#include "tools/colmap/colmap_poses.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

constexpr const char* kUsage = R"(usage: lc2wf-colmap-poses --views DIR [options]

Runs COLMAP (feature_extractor, exhaustive_matcher, mapper; CPU) on the images of DIR (*.png, *.jpg, in
name order) with fixed pinhole intrinsics and writes DIR/cameras_colmap.json (K, R, t per image in the
OpenCV convention, null for unregistered images). Intrinsics come from --intrinsics or DIR/cameras.json;
with DIR/cameras.json the poses are aligned to those cameras (similarity) and the errors are printed.

options:
  --intrinsics fx,fy,cx,cy   OpenCV pixel convention (centre of the top-left pixel = 0,0)
  --workspace DIR            COLMAP working folder (default DIR/colmap)
  --colmap PATH              COLMAP executable (default colmap)
  -h, --help                 this text

exit codes: 0 ok, 2 bad arguments, 3 COLMAP or I/O failure
)";

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "lc2wf-colmap-poses: %s\n(run with --help for usage)\n", msg.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  fs::path views, workspace;
  std::string intrinsics;
  lc2wf::ColmapOptions opts;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--views") {
      views = value();
    } else if (a == "--workspace") {
      workspace = value();
    } else if (a == "--intrinsics") {
      intrinsics = value();
    } else if (a == "--colmap") {
      opts.executable = value();
    } else {
      usage_error("unknown argument '" + a + "'");
    }
  }
  if (views.empty()) usage_error("--views DIR is required");
  if (!fs::is_directory(views)) usage_error("not a folder: " + views.string());
  if (workspace.empty()) workspace = views / "colmap";
  try {
    std::vector<fs::path> images;
    for (const auto& e : fs::directory_iterator(views)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg")) images.push_back(e.path());
    }
    std::sort(images.begin(), images.end());
    if (images.size() < 3) throw std::runtime_error(views.string() + ": fewer than 3 images");
    std::vector<lc2wf::Camera> reference;
    if (fs::exists(views / "cameras.json")) {
      const fs::path cameras = views / "cameras.json";
      for (const Json& j : Json::parse(lc2wf::read_file(cameras)))
        reference.push_back(lc2wf::camera_from_json(j, cameras.string()));
      if (reference.size() != images.size())
        throw std::runtime_error(views.string() + ": cameras.json has " + std::to_string(reference.size()) + " cameras for " +
                                 std::to_string(images.size()) + " images");
    }
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    int width = 0, height = 0;
    if (!intrinsics.empty()) {
      double fx, fy, cx, cy;
      if (std::sscanf(intrinsics.c_str(), "%lf,%lf,%lf,%lf", &fx, &fy, &cx, &cy) != 4) usage_error("--intrinsics expects fx,fy,cx,cy");
      K << fx, 0, cx, 0, fy, cy, 0, 0, 1;
    } else if (!reference.empty()) {
      K = reference.front().K;
      width = reference.front().width;
      height = reference.front().height;
    } else {
      usage_error("no intrinsics: pass --intrinsics or provide DIR/cameras.json");
    }
    auto poses = lc2wf::estimate_poses_with_colmap(images, K, width, height, workspace, opts);
    Json report;
    report["images"] = images.size();
    report["registered"] = std::count_if(poses.begin(), poses.end(), [](const auto& p) { return p.has_value(); });
    if (!reference.empty()) {
      const auto pc = lc2wf::align_to_reference(reference, poses);
      report["scale_to_reference"] = pc.scale;
      report["centre_error"] = {{"median", pc.median_centre_error}, {"max", pc.max_centre_error}};
      report["rotation_error_deg"] = {{"median", pc.median_rotation_deg}, {"max", pc.max_rotation_deg}};
    }
    Json out = Json::array();
    for (const auto& p : poses) out.push_back(p ? lc2wf::camera_to_json(*p) : Json(nullptr));
    lc2wf::write_file_atomic(views / "cameras_colmap.json", out.dump());
    std::cout << report.dump(2) << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-colmap-poses: %s\n", e.what());
    return 3;
  }
}
