// Locating and loading what lc2wf-eval compares: split lists, ground-truth wireframes (OBJ, Roof-Image
// polyshape or line-cloud files) and predictions, all converted to metres.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/splits/splits.h"  // read_name_list
#include "model/scored_wireframe.h"

namespace lc2wf {

enum class CoordinateUnits { kMetres, kRaw };

struct GroundTruthSource {
  enum class Kind { kMeshDir, kLineCloudDir };
  Kind kind = Kind::kMeshDir;
  std::filesystem::path dir;
  CoordinateUnits obj_units = CoordinateUnits::kMetres;  // units of GT `.obj` files
  bool obj_y_up = false;        // GT OBJs exported Y-up (Roof-Image res_obj, LC2WF house/): swap to Z-up
  double raw_per_metre = kRawUnitsPerMetre;  // raw units per metre of GT .obj files and release JSON
  std::string lod;              // city-model GT: the LoD 2.x to read (empty: each building's highest)
  // Line-cloud GT only: keep the GT edges at least this many of the cloud's cameras had in view (0: the whole
  // wireframe), so a street capture is scored on what it saw (model/edge_visibility.h, seen_part).
  int seen_by_cameras = 0;
};

struct GroundTruth {
  std::filesystem::path path;
  Wireframe wireframe;  // metres
  UnitTransform units;  // how this building's raw coordinates map to metres (used for raw predictions)
  // False for .obj files in metres: no transform of their own, so they are taken to be in the cloud's frame.
  bool has_own_frame = true;
  std::vector<Segment3> cloud_segments;  // line-cloud sources only: the cloud (metres), for reports and frames
  PolyMesh mesh;  // Roof-Image polyshapes only: the labelled faces (metres), for the face metrics
};

// The file of `name` in the source folder: `<name>.obj` or `<name>.polyshape` (mesh folder; both present is
// an error), or the single file whose stem is `name` (line-cloud folder). nullopt when there is none.
std::optional<std::filesystem::path> find_ground_truth(const GroundTruthSource& source, const std::string& name);

// Loads a GT file found by find_ground_truth. Polyshapes go through the dataset layer's building import
// (metres, footprint recentred); line clouds (ours, or the release's LineCloud JSON with `objGTJunc3D` /
// `line_idx`) carry their own wireframe and transform. Throws DataError.
// A city-model file holds many buildings: pass the building's name with it. A building the LoD2 clean-up
// rejects throws Lod2Skipped (a BuildingSkipped).
GroundTruth load_ground_truth(const GroundTruthSource& source, const std::filesystem::path& path, const std::string& name = "");

// A point in the metric frame of a line cloud with `cloud_units` (a prediction made on it, or its segments), in
// the GT's metric frame: each frame maps to the building's raw source coordinates, the one frame they share
// (a cloud's origin need not be the GT's bounding-box centre). Unchanged when the GT has no frame of its own.
Vec3 cloud_to_ground_truth_frame(const Vec3& p, const UnitTransform& cloud_units, const GroundTruth& gt);

// Names of every GT building in the source folder (sorted); used when no split file is given.
std::vector<std::string> list_ground_truth_names(const GroundTruthSource& source);

}  // namespace lc2wf
