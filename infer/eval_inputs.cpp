#include "infer/eval_inputs.h"

#include <algorithm>
#include <set>

#include "dataset/atomic_file.h"
#include "dataset/building.h"
#include "dataset/errors.h"
#include "dataset/line_cloud_io.h"
#include "dataset/mesh_io.h"
#include "dataset/release_json.h"
#include "dataset/text_parse.h"

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
  // Line clouds: the dataset layer fixes the content, not the extension, so match on the stem.
  std::vector<fs::path> hits;
  std::error_code type_ec;  // a symlink loop is not a folder: its reader names it
  for (const auto& entry : fs::directory_iterator(source.dir))
    if (!entry.is_directory(type_ec) && entry.path().stem() == name) hits.push_back(entry.path());  // folders: LIMAP runs, plots
  if (hits.size() > 1) {
    std::sort(hits.begin(), hits.end());
    throw DataError(source.dir.string(), "several files named '" + name + "' (" + hits[0].filename().string() + ", " +
                                             hits[1].filename().string() + "); keep one line cloud per building");
  }
  if (hits.empty()) return std::nullopt;
  return hits[0];
}

GroundTruth load_ground_truth(const GroundTruthSource& source, const fs::path& path) {
  GroundTruth gt;
  gt.path = path;
  if (source.kind == GroundTruthSource::Kind::kLineCloudDir) {
    // Our line-cloud files and the release's LineCloud JSON both may start with '{'; the release keys tell.
    const std::string bytes = read_file(path);
    const bool release = bytes.find("\"junc3DList\"") != std::string::npos &&
                         bytes.find("\"lc2wf-linecloud\"") == std::string::npos;
    LineCloud cloud = release ? parse_release_line_cloud(bytes, path.string()) : line_cloud_from_bytes(bytes, path.string());
    if (cloud.wireframe.junctions.empty())
      throw DataError(path.string(), "line cloud has no ground-truth wireframe");
    gt.wireframe = std::move(cloud.wireframe);
    gt.units = cloud.units;
    gt.cloud_segments = std::move(cloud.segments);
  } else if (path.extension() == ".polyshape") {
    Building b = load_roof_image_building(path);
    gt.wireframe = std::move(b.wireframe);
    gt.units = b.units;
  } else {
    ObjReadOptions o;
    o.y_up = source.obj_y_up;
    gt.wireframe = read_obj_wireframe(path, o);
    if (source.obj_units == CoordinateUnits::kRaw) {
      gt.units.raw_per_metre = source.raw_per_metre;
      for (Vec3& p : gt.wireframe.junctions) p = gt.units.to_metres(p);
    }
  }
  return gt;
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
