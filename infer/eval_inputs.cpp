#include "infer/eval_inputs.h"

#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

#include "dataset/formats/building_sources.h"
#include "dataset/geometry/building.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"
#include "model/edge_support.h"
#include "model/edge_visibility.h"

namespace lc2wf {
namespace fs = std::filesystem;

namespace {

// Any entry counts, not only regular files: a FIFO or folder under a building's name is then refused by
// the reader, naming it, instead of the building being reported as missing.
bool present(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

// The buildings of a mesh folder (polyshapes, city models), listed once per folder, LoD and modification
// time: each city-model file is then parsed once for all its buildings, not once per building.
const BuildingCatalog& mesh_catalog(const GroundTruthSource& source) {
  static std::mutex mu;
  static std::map<std::tuple<std::string, std::string, fs::file_time_type>, std::unique_ptr<BuildingCatalog>> catalogs;
  std::lock_guard<std::mutex> lock(mu);
  std::error_code ec;
  const fs::file_time_type changed = fs::last_write_time(source.dir, ec);
  auto& c = catalogs[{source.dir.string(), source.lod, ec ? fs::file_time_type{} : changed}];
  if (!c) {
    BuildingSourceOptions o;
    o.lod = source.lod;
    c = std::make_unique<BuildingCatalog>(source.dir, o);
    for (const SourceFileListing& f : c->files())
      if (!f.error.empty()) std::fprintf(stderr, "lc2wf-eval: skipped ground-truth file %s\n", f.error.c_str());
  }
  return *c;
}

}  // namespace

std::optional<fs::path> find_ground_truth(const GroundTruthSource& source, const std::string& name) {
  if (source.kind == GroundTruthSource::Kind::kMeshDir) {
    const fs::path obj = source.dir / (name + ".obj");
    const BuildingEntry* model = mesh_catalog(source).find(name);  // .polyshape or a city model
    const bool has_obj = !fs::is_regular_file(source.dir) && present(obj);
    if (has_obj && model)
      throw DataError(source.dir.string(), "both " + obj.filename().string() + " and " + model->file.filename().string() +
                                               " hold '" + name + "'; keep one ground truth per building");
    if (has_obj) return obj;
    if (model) return model->file;
    return std::nullopt;
  }
  return find_cloud_file_if_any(source.dir, name);
}

GroundTruth load_ground_truth(const GroundTruthSource& source, const fs::path& path, const std::string& name) {
  GroundTruth gt;
  gt.path = path;
  if (source.kind == GroundTruthSource::Kind::kLineCloudDir) {
    LineCloud cloud = load_line_cloud(path, CloudFormat::kAuto, source.raw_per_metre);
    if (cloud.wireframe.junctions.empty())
      throw DataError(path.string(), "line cloud has no ground-truth wireframe");
    gt.wireframe = std::move(cloud.wireframe);
    if (source.seen_by_cameras > 0) {
      if (cloud.cameras.empty()) throw DataError(path.string(), "line cloud has no cameras, so --gt-seen-by cannot tell what they saw");
      gt.wireframe = seen_part(gt.wireframe, cloud.cameras, source.seen_by_cameras, EdgeSupportOptions{}.occlusion_tolerance_m);
    }
    gt.units = cloud.units;
    gt.cloud_segments = std::move(cloud.segments);
  } else if (path.extension() == ".polyshape" || is_city_model_file_name(path)) {
    if (is_city_model_file_name(path) && name.empty()) throw DataError(path.string(), "a city model needs the building's name");
    Building b = is_city_model_file_name(path) ? mesh_catalog(source).load(name) : load_roof_image_building(path);
    gt.wireframe = std::move(b.wireframe);
    gt.units = b.units;
    gt.mesh = std::move(b.mesh);
  } else {
    ObjReadOptions o;
    o.y_up = source.obj_y_up;
    gt.wireframe = read_obj_wireframe(path, o);
    gt.has_own_frame = source.obj_units == CoordinateUnits::kRaw;
    if (source.obj_units == CoordinateUnits::kRaw) {
      gt.units.raw_per_metre = source.raw_per_metre;
      for (Vec3& p : gt.wireframe.junctions) p = gt.units.to_metres(p);
    }
  }
  return gt;
}

Vec3 cloud_to_ground_truth_frame(const Vec3& p, const UnitTransform& cloud_units, const GroundTruth& gt) {
  return gt.has_own_frame ? gt.units.to_metres(cloud_units.to_raw(p)) : p;
}

std::vector<std::string> list_ground_truth_names(const GroundTruthSource& source) {
  std::set<std::string> names;
  if (source.kind == GroundTruthSource::Kind::kMeshDir) {
    const auto models = mesh_catalog(source).names();
    names.insert(models.begin(), models.end());
  }
  if (fs::is_regular_file(source.dir)) return {names.begin(), names.end()};
  for (const auto& entry : fs::directory_iterator(source.dir)) {
    const fs::path& p = entry.path();
    // Mesh folders: every *.obj / *.polyshape entry (a FIFO among them fails by name); line-cloud folders
    // may hold other things (plots, LIMAP runs), so only their regular files are buildings.
    if (source.kind == GroundTruthSource::Kind::kLineCloudDir ? entry.is_regular_file()
                                                              : p.extension() == ".obj")
      names.insert(p.stem().string());
  }
  return {names.begin(), names.end()};
}

}  // namespace lc2wf
