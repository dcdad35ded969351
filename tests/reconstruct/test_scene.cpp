#include "test_scene.h"

#include <unistd.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "dataset/synthetic/synthetic_building.h"
#include "nn/checkpoint.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "tools/render/camera_ring.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf::test {

namespace fs = std::filesystem;

RenderedFolder render_synthetic_folder(const fs::path& dir, int views) {
  return render_synthetic_folder(dir, views, make_l_building("l", LBuildingSpec{}), "paper");
}

RenderedFolder render_synthetic_folder(const fs::path& dir, int views, const Building& building, const std::string& textures) {
  RenderedFolder f;
  f.building = building;
  CameraRingOptions ring;
  ring.views = views;
  ring.seed = 4;
  f.cameras = make_camera_ring(f.building.mesh.vertices, ring);
  RasterOptions raster;
  raster.seed = 9;
  raster.textures = textures;
  PhotoScene scene;
  if (textures == "photo") {
    std::vector<Vec3> centres;
    for (const Camera& c : f.cameras) centres.push_back(c.center());
    scene = make_photo_scene(f.building.mesh, centres, PhotoOptions{}, 9);
  }
  const RasterRenderer renderer(f.building.mesh, raster, scene);
  f.images = dir / "images";
  fs::create_directories(f.images);
  nlohmann::json cams = nlohmann::json::array();
  for (int v = 0; v < views; ++v) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03d.png", v);
    cv::imwrite((f.images / name).string(), renderer.render(f.cameras[v], v).image);
    cams.push_back(camera_to_json(f.cameras[v]));
  }
  f.cameras_json = dir / "cameras.json";
  write_file_atomic(f.cameras_json, cams.dump());
  return f;
}



fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_reconstruct_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Similarity similarity_from_json(const nlohmann::json& j) {
  Similarity s;
  s.scale = j["scale"].get<double>();
  for (int k = 0; k < 9; ++k) s.R(k / 3, k % 3) = j["R"][k].get<double>();
  for (int k = 0; k < 3; ++k) s.t[k] = j["t"][k].get<double>();
  return s;
}

}  // namespace lc2wf::test
