// Drives tools/blender/render_building.py: one Blender process renders every view of a batch of
// buildings; the images, the cameras Blender actually used (read back as OpenCV K, R, t) and the
// per-view GT edge visibility come back per building, or the reason it failed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dataset/geometry/building.h"
#include "tools/pipeline/cloud_builder.h"
#include "tools/render/photo_scene.h"

namespace lc2wf {

struct BlenderOptions {
  std::string executable = "blender";
  std::filesystem::path script;                 // empty: the render_building.py of this source tree
  std::string engine = "BLENDER_WORKBENCH";     // or BLENDER_EEVEE, CYCLES
  // Workbench: 1 = no anti-aliasing. Each AA sample is a full llvmpipe pass: 5 samples cost ~3x the
  // whole Blender path for +3 points GT-edge coverage (tools/README.md).
  int samples = 1;
  bool shadows = true;
  std::string textures = "paper";               // or "sfm": non-repeating noise that COLMAP can match; or "photo"
  double sun_azimuth_deg = 140.0;
  double sun_elevation_deg = 55.0;
  int threads = 0;                              // Blender's -t (0 = all cores)
  bool gt_views = true;                         // write views.json (projected GT with visibility ray casts)
  void Check() const;
};

struct BlenderBuilding {
  const Building* building = nullptr;
  std::vector<Camera> cameras;
  std::filesystem::path out_dir;  // renders and metadata go here
  uint64_t seed = 0;
  const PhotoScene* scene = nullptr;  // textures "photo": windows, clutter objects, sun, per-view exposure
};

struct BlenderResult {
  std::vector<RenderedView> views;  // empty on failure
  std::string error;                // empty on success
};

// Path of the Blender script shipped with this source tree.
std::filesystem::path default_blender_script();

// Renders the batch in one Blender process. A building's failure (bad mesh, Blender error or crash) is
// reported in its result; throws std::runtime_error only when the job file cannot be written.
std::vector<BlenderResult> render_with_blender(const std::vector<BlenderBuilding>& batch, const BlenderOptions& options,
                                               const std::filesystem::path& work_dir);

// Reads one building's Blender output folder (views, cameras.json); throws DataError naming the folder.
std::vector<RenderedView> read_blender_output(const std::filesystem::path& dir);

}  // namespace lc2wf
