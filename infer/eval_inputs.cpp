#include "infer/eval_inputs.h"

#include <set>

#include "dataset/geometry/building.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"

namespace lc2wf {
namespace fs = std::filesystem;

namespace {

// Any entry counts, not only regular files: a FIFO or folder under a building's name is then refused by
// the reader, naming it, instead of the building being reported as missing.
bool present(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

}  // namespace

std::optional<fs::path> find_ground_truth(const GroundTruthSource& source, const std::string& name) {
  if (source.kind == GroundTruthSource::Kind::kMeshDir) {
    const fs::path obj = source.dir / (name + ".obj");
    const fs::path poly = source.dir / (name + ".polyshape");
    const bool has_obj = present(obj), has_poly = present(poly);
    if (has_obj && has_poly)
      throw DataError(source.dir.string(), "both " + obj.filename().string() + " and " + poly.filename().string() +
                                               " exist; keep one ground truth per building");
    if (has_obj) return obj;
    if (has_poly) return poly;
    return std::nullopt;
  }
  return find_cloud_file_if_any(source.dir, name);
}

GroundTruth load_ground_truth(const GroundTruthSource& source, const fs::path& path) {
  GroundTruth gt;
  gt.path = path;
  if (source.kind == GroundTruthSource::Kind::kLineCloudDir) {
    LineCloud cloud = load_line_cloud(path, CloudFormat::kAuto, source.raw_per_metre);
    if (cloud.wireframe.junctions.empty())
      throw DataError(path.string(), "line cloud has no ground-truth wireframe");
    gt.wireframe = std::move(cloud.wireframe);
    gt.units = cloud.units;
    gt.cloud_segments = std::move(cloud.segments);
  } else if (path.extension() == ".polyshape") {
    Building b = load_roof_image_building(path);
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
  for (const auto& entry : fs::directory_iterator(source.dir)) {
    const fs::path& p = entry.path();
    // Mesh folders: every *.obj / *.polyshape entry (a FIFO among them fails by name); line-cloud folders
    // may hold other things (plots, LIMAP runs), so only their regular files are buildings.
    if (source.kind == GroundTruthSource::Kind::kLineCloudDir ? entry.is_regular_file()
                                                              : p.extension() == ".obj" || p.extension() == ".polyshape")
      names.insert(p.stem().string());
  }
  return {names.begin(), names.end()};
}

}  // namespace lc2wf
