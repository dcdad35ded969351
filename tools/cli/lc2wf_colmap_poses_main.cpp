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

Json camera_json(const lc2wf::Camera& c) {
  Json j;
  j["K"] = {c.K(0, 0), c.K(0, 1), c.K(0, 2), c.K(1, 0), c.K(1, 1), c.K(1, 2), c.K(2, 0), c.K(2, 1), c.K(2, 2)};
  j["R"] = {c.R(0, 0), c.R(0, 1), c.R(0, 2), c.R(1, 0), c.R(1, 1), c.R(1, 2), c.R(2, 0), c.R(2, 1), c.R(2, 2)};
  j["t"] = {c.t.x(), c.t.y(), c.t.z()};
  j["width"] = c.width;
  j["height"] = c.height;
  return j;
}

lc2wf::Camera camera_from_json(const Json& j) {
  lc2wf::Camera c;
  const auto K = j.at("K").get<std::vector<double>>(), R = j.at("R").get<std::vector<double>>();
  const auto t = j.at("t").get<std::vector<double>>();
  if (K.size() != 9 || R.size() != 9 || t.size() != 3) throw std::runtime_error("camera needs K[9], R[9], t[3]");
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c.K(r, k) = K[3 * r + k], c.R(r, k) = R[3 * r + k];
  c.t = lc2wf::Vec3(t[0], t[1], t[2]);
  c.width = j.at("width").get<int>();
  c.height = j.at("height").get<int>();
  return c;
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
      for (const Json& j : Json::parse(lc2wf::read_file(views / "cameras.json"))) reference.push_back(camera_from_json(j));
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
    for (const auto& p : poses) out.push_back(p ? camera_json(*p) : Json(nullptr));
    lc2wf::write_file_atomic(views / "cameras_colmap.json", out.dump());
    std::cout << report.dump(2) << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-colmap-poses: %s\n", e.what());
    return 3;
  }
}
