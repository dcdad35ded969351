#include "tools/render/blender_renderer.h"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "dataset/formats/errors.h"
#include "tools/process/run_process.h"

namespace lc2wf {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

// Last non-empty line of a text file (the exception line of a Python traceback).
std::string last_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

// The photo scene as the script reads it: clutter faces with their kind and object, facade rectangles per
// face, the ground layout, the sun and each view's exposure.
Json photo_scene_json(const PhotoScene& scene, size_t views, uint64_t seed) {
  static const char* kKinds[] = {"chimney", "balcony", "car_body", "car_cabin", "trunk", "foliage", "neighbour_wall", "neighbour_roof"};
  Json p;
  Json verts = Json::array(), kinds = Json::array(), facades = Json::array(), paths = Json::array(), exposure = Json::array();
  for (const Vec3& v : scene.clutter.vertices) verts.push_back({v.x(), v.y(), v.z()});
  for (ClutterKind k : scene.kinds) kinds.push_back(kKinds[static_cast<int>(k)]);
  auto rects = [](const std::vector<FacadeRect>& rs) {
    Json a = Json::array();
    for (const FacadeRect& r : rs) a.push_back({r.u0, r.u1, r.z0, r.z1});
    return a;
  };
  for (const FacadeLayout& f : scene.facades)
    facades.push_back({{"wall", f.wall}, {"storey_height", f.storey_height}, {"ground_z", f.ground_z}, {"top_z", f.top_z},
                       {"peak_z", f.peak_z}, {"windows", rects(f.windows)}, {"doors", rects(f.doors)}});
  for (const auto& path : scene.ground.paths) paths.push_back({path[0].x(), path[0].y(), path[1].x(), path[1].y()});
  for (size_t v = 0; v < views; ++v) exposure.push_back(view_photometry(scene.options, seed, v).exposure);
  p["clutter_vertices"] = verts;
  p["clutter_faces"] = scene.clutter.faces;
  p["clutter_kinds"] = kinds;
  p["clutter_objects"] = scene.objects;
  p["facades"] = facades;
  p["storey_height"] = scene.storey_height;
  p["road"] = scene.ground.road ? Json{{"point", {scene.ground.road_point.x(), scene.ground.road_point.y()}},
                                       {"dir", {scene.ground.road_dir.x(), scene.ground.road_dir.y()}},
                                       {"half_width", scene.ground.road_half_width}}
                                 : Json();
  p["paths"] = paths;
  p["path_half_width"] = scene.ground.path_half_width;
  p["sun_azimuth_deg"] = scene.sun_azimuth_deg;
  p["sun_elevation_deg"] = scene.sun_elevation_deg;
  p["vary_sun"] = scene.options.vary_sun;
  p["roof_tiles"] = scene.options.roof_tiles;
  p["gutters"] = scene.options.gutters;
  p["exposure"] = exposure;
  return p;
}

}  // namespace

void BlenderOptions::Check() const {
  if (executable.empty()) throw std::invalid_argument("BlenderOptions.executable is empty");
  if (engine != "BLENDER_WORKBENCH" && engine != "BLENDER_EEVEE" && engine != "CYCLES")
    throw std::invalid_argument("BlenderOptions.engine must be BLENDER_WORKBENCH, BLENDER_EEVEE or CYCLES, not " + engine);
  if (samples < 1) throw std::invalid_argument("BlenderOptions.samples must be >= 1");
  if (textures != "paper" && textures != "sfm" && textures != "photo")
    throw std::invalid_argument("BlenderOptions.textures must be paper, sfm or photo, not " + textures);
  if (threads < 0) throw std::invalid_argument("BlenderOptions.threads must be >= 0");
  if (sun_elevation_deg <= 0 || sun_elevation_deg > 90) throw std::invalid_argument("BlenderOptions.sun_elevation_deg must be in (0, 90]");
}

fs::path default_blender_script() {
  if (const char* env = std::getenv("LC2WF_BLENDER_SCRIPT")) return env;
  return fs::path(LC2WF_TOOLS_SOURCE_DIR) / "blender" / "render_building.py";
}

std::vector<RenderedView> read_blender_output(const fs::path& dir) {
  const fs::path cams_path = dir / "cameras.json";
  if (!fs::exists(dir / "done.json")) throw DataError(dir.string(), "Blender did not finish this building (no done.json)");
  Json cams;
  try {
    cams = Json::parse(read_file(cams_path));
  } catch (const Json::exception& e) {
    throw DataError(cams_path.string(), std::string("bad JSON: ") + e.what());
  }
  if (!cams.is_array() || cams.empty()) throw DataError(cams_path.string(), "no cameras");
  std::vector<RenderedView> views;
  for (size_t i = 0; i < cams.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu.png", i);
    RenderedView v;
    v.camera = camera_from_json(cams[i], cams_path.string());
    v.image = cv::imread((dir / name).string(), cv::IMREAD_COLOR);
    if (v.image.empty()) throw DataError((dir / name).string(), "missing or unreadable render");
    if (v.image.cols != v.camera.width || v.image.rows != v.camera.height)
      throw DataError((dir / name).string(), "image size differs from the camera's");
    views.push_back(std::move(v));
  }
  return views;
}

std::vector<BlenderResult> render_with_blender(const std::vector<BlenderBuilding>& batch, const BlenderOptions& options,
                                               const fs::path& work_dir) {
  options.Check();
  std::vector<BlenderResult> results(batch.size());
  if (batch.empty()) return results;
  fs::create_directories(work_dir);
  Json job;
  job["engine"] = options.engine;
  job["samples"] = options.samples;
  job["shadows"] = options.shadows;
  job["gt_views"] = options.gt_views;
  job["textures"] = options.textures;
  job["sun_azimuth_deg"] = options.sun_azimuth_deg;
  job["sun_elevation_deg"] = options.sun_elevation_deg;
  job["buildings"] = Json::array();
  for (const BlenderBuilding& b : batch) {
    fs::remove_all(b.out_dir);  // stale output from a killed run must not count as done
    Json j;
    j["name"] = b.building->name;
    j["out_dir"] = fs::absolute(b.out_dir).string();
    j["seed"] = b.seed;
    Json verts = Json::array(), faces = Json::array(), labels = Json::array(), edges = Json::array(), cams = Json::array();
    Json gt_junctions = Json::array();
    for (const Vec3& v : b.building->mesh.vertices) verts.push_back({v.x(), v.y(), v.z()});
    for (const Vec3& v : b.building->wireframe.junctions) gt_junctions.push_back({v.x(), v.y(), v.z()});
    for (const auto& f : b.building->mesh.faces) faces.push_back(f);
    for (size_t f = 0; f < b.building->mesh.faces.size(); ++f)
      labels.push_back(b.building->mesh.labels.empty() ? 3 : static_cast<int>(b.building->mesh.labels[f]));
    for (const auto& e : b.building->wireframe.edges) edges.push_back({e[0], e[1]});
    for (const Camera& c : b.cameras) cams.push_back(camera_to_json(c));
    j["vertices"] = verts;
    j["faces"] = faces;
    j["labels"] = labels;
    j["edges"] = edges;
    j["gt_junctions"] = gt_junctions;
    j["cameras"] = cams;
    if (options.textures == "photo" && b.scene) j["photo"] = photo_scene_json(*b.scene, b.cameras.size(), b.seed);
    job["buildings"].push_back(j);
  }
  const fs::path job_path = work_dir / "job.json", log_path = work_dir / "blender.log";
  write_file_atomic(job_path, job.dump());
  const fs::path script = options.script.empty() ? default_blender_script() : options.script;
  // An argument vector, no shell: paths with spaces or quotes reach Blender as they are.
  std::vector<std::string> argv = {options.executable, "-b", "--factory-startup"};
  if (options.threads > 0) argv.insert(argv.end(), {"-t", std::to_string(options.threads)});
  argv.insert(argv.end(), {"--python-exit-code", "1", "--python", script.string(), "--", job_path.string()});
  std::ofstream(log_path, std::ios::trunc).close();  // one batch per log, as before
  const ProcessResult run = run_process(argv, log_path);
  std::string process_error;
  if (run.signal) {
    process_error = "Blender was killed by signal " + std::to_string(run.signal) + " (log: " + log_path.string() + ")";
  } else if (run.exit_code < 0) {
    process_error = "could not start Blender (" + options.executable + ": not found or not executable)";
  } else if (run.exit_code != 0) {
    process_error = "Blender exited with code " + std::to_string(run.exit_code) + ": " + last_line(log_path) + " (log: " +
                    log_path.string() + ")";
  }
  for (size_t i = 0; i < batch.size(); ++i) {
    const fs::path& dir = batch[i].out_dir;
    if (fs::exists(dir / "error.txt")) {
      results[i].error = "Blender failed on this building: " + last_line(dir / "error.txt");
      continue;
    }
    if (!fs::exists(dir / "done.json")) {
      results[i].error = process_error.empty() ? "Blender produced no output for this building (log: " + log_path.string() + ")" : process_error;
      continue;
    }
    try {
      results[i].views = read_blender_output(dir);
    } catch (const std::exception& e) {
      results[i].error = e.what();
    }
  }
  return results;
}

}  // namespace lc2wf
