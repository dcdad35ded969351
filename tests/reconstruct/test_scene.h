// Shared scenes for the reconstruct tests: a folder of raster renders of a synthetic building with its
// cameras.json, and tiny randomly initialised networks (the pipeline runs; the wireframe is not judged).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/geometry/building.h"
#include "dataset/photo/metric_frame.h"
#include "tests/common/tiny_weights.h"  // write_tiny_weights

namespace lc2wf::test {

struct RenderedFolder {
  std::filesystem::path images;  // view_XXX.png
  std::filesystem::path cameras_json;
  std::vector<Camera> cameras;
  Building building;
};

// `views` raster renders (640x480, paper textures) of an L-shaped building into dir/images, the cameras
// into dir/cameras.json (kept outside the image folder). Or of `building` with `textures` (photo: windows by
// storey, clutter).
RenderedFolder render_synthetic_folder(const std::filesystem::path& dir, int views);
RenderedFolder render_synthetic_folder(const std::filesystem::path& dir, int views, const Building& building, const std::string& textures);

// A similarity as report.json stores it ({"scale", "R" row-major, "t"}).
Similarity similarity_from_json(const nlohmann::json& j);

// A fresh scratch folder per test and process.
std::filesystem::path scratch(const std::string& name);

}  // namespace lc2wf::test
