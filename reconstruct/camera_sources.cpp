#include "reconstruct/camera_sources.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "reconstruct/stage_error.h"

namespace lc2wf {

namespace fs = std::filesystem;

namespace {

CameraSet from_json(const fs::path& path, const std::vector<std::string>& all_names, const std::vector<fs::path>& images) {
  CameraSet set;
  set.source = "cameras json";
  set.metric_z_up = true;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw StageError("cameras", path.string() + ": not JSON: " + e.what());
  }
  if (!j.is_array()) throw StageError("cameras", path.string() + ": expected an array of cameras (one per image, null = unknown)");
  if (j.size() != all_names.size())
    throw StageError("cameras", path.string() + " has " + std::to_string(j.size()) + " cameras for " + std::to_string(all_names.size()) +
                                    " images (one entry per image file, in name order)");
  for (const fs::path& image : images) {
    const size_t i = static_cast<size_t>(std::find(all_names.begin(), all_names.end(), image.filename().string()) - all_names.begin());
    set.cameras.push_back(j[i].is_null() ? std::nullopt
                                         : std::optional<Camera>(camera_from_json(j[i], path.string() + " entry " + std::to_string(i))));
  }
  return set;
}

}  // namespace

CameraSet cameras_from_file(const fs::path& path, const std::vector<std::string>& all_names, const std::vector<fs::path>& images) {
  try {
    if (!fs::is_directory(path)) return from_json(path, all_names, images);
    CameraSet set;
    set.source = "colmap model";
    set.cameras.resize(images.size());
    const std::vector<ColmapImage> model = read_colmap_model(path);
    int matched = 0;
    for (const ColmapImage& im : model)
      for (size_t i = 0; i < images.size(); ++i)
        if (images[i].filename() == fs::path(im.name).filename()) set.cameras[i] = im.camera, ++matched;
    if (matched == 0 && !model.empty() && !images.empty())
      throw StageError("cameras", path.string() + ": none of the model's " + std::to_string(model.size()) +
                                      " image names matches an image of the folder (model: '" + model.front().name + "', folder: '" +
                                      images.front().filename().string() + "', ...)");
    return set;
  } catch (const StageError&) {
    throw;
  } catch (const std::exception& e) {
    throw StageError("cameras", e.what());
  }
}

CameraSet cameras_from_colmap(const std::vector<fs::path>& images, const std::vector<Eigen::Matrix3d>& K, const fs::path& workspace,
                              const ColmapOptions& options) {
  try {
    ColmapRun run = estimate_poses_with_colmap(images, K, workspace, options);
    CameraSet set;
    set.source = "colmap";
    set.cameras = std::move(run.cameras);
    set.step_seconds = std::move(run.step_seconds);
    set.focal_refined = run.focal_refined;
    return set;
  } catch (const std::exception& e) {
    throw StageError("cameras", e.what());
  }
}

}  // namespace lc2wf
