// lc2wf-dataset's engine: for every building of a shard, render -> 2D lines -> 3D line cloud -> labels
// -> write, atomically per building, skipping buildings already done (a killed run loses at most the
// buildings in flight), with a progress bar and a JSON summary of the whole shard.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dataset/formats/building_sources.h"
#include "tools/pipeline/cloud_builder.h"
#include "tools/render/blender_renderer.h"
#include "tools/render/camera_ring.h"
#include "tools/render/capture_kind.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf {

enum class RendererKind { Raster, Blender };

struct DatasetRunOptions {
  std::filesystem::path meshes;  // folder or file of buildings: .polyshape, CityJSON, CityJSONSeq, CityGML
  std::filesystem::path out;
  RendererKind renderer = RendererKind::Raster;
  CameraRingOptions cameras;
  // Finer images for larger buildings (tools/render/camera_ring.h, view_scale_for): each building's images
  // grow until its bounding-box diagonal takes at most this many metres per pixel of width (0 = cameras'
  // width x height for every building), never beyond max_image_side pixels; LSD's length and count limits
  // follow (tools/lines/lsd_detector.h, scaled_lsd). 0.05 leaves a 640-px-wide view of a building whose
  // diagonal is up to 32 m as it was (most houses, 95 % of Roof-Image) and sharpens the larger ones
  // (tools/README.md, "Scene").
  double max_metres_per_pixel = 0.05;
  int max_image_side = 4096;
  std::string capture = "orbit";  // orbit, street-1, street-2 or walk: the ring as set, or a street capture of it (render/capture_kind.h)
  RasterOptions raster;
  BlenderOptions blender;
  PhotoOptions photo;            // the scene of `--textures photo` (both renderers)
  int blender_batch = 16;        // buildings per Blender process (its start-up is shared)
  CloudBuilderOptions cloud;
  BuildingOptions building;
  BuildingSourceOptions sources;  // city models: LoD and LoD2 clean-up (dataset/formats/building_sources.h)
  int threads = 0;               // 0 = all cores
  int shard_index = 0;           // this process handles buildings k with k % shard_count == shard_index
  int shard_count = 1;
  int limit = 0;                 // at most this many buildings of the shard (0 = all)
  std::filesystem::path names;   // a name list (e.g. configs/splits/lod2/val.txt): only these buildings (empty = all)
  uint64_t seed = 0;             // cameras, textures and noise; combined with each building's name
  bool keep_views = false;       // keep renders, cameras and per-view GT visibility under out/views/
  bool progress = true;
  std::vector<std::string> command_line;  // recorded in the summary with the lc2wf version and commit
  void Check() const;
};

// Output layout under `out`: clouds/<name>.lcloud (dataset/ line-cloud format), status/<name>.json (one
// per processed building: counts, timings or the failure reason), views/<name>/ (with keep_views), and
// summary.json (summary-shard-<i>-of-<n>.json when sharded). Returns the summary. Throws
// std::invalid_argument for bad options and DataError when the mesh folder cannot be listed.
nlohmann::json run_dataset(const DatasetRunOptions& options);

// Buildings of one shard, in name order, after the limit.
std::vector<std::string> shard_names(const std::vector<std::string>& sorted_names, int shard_index, int shard_count, int limit);

// Per-building seed: independent of sharding and order.
uint64_t building_seed(const std::string& name, uint64_t seed);

// Summary over per-building status records (the JSON written to status/<name>.json).
nlohmann::json summarise(const std::vector<nlohmann::json>& statuses);

}  // namespace lc2wf
