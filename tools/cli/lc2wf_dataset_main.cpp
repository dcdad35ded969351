// lc2wf-dataset: Roof-Image meshes -> labelled 3D line clouds (render, LSD, triangulation, labels).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include "core/util/cli.h"
#include "core/util/json_text.h"
#include "tools/pipeline/dataset_run.h"

namespace {

constexpr const char* kUsage = R"(Usage: lc2wf-dataset --meshes DIR -o OUT [options]

Renders every building of DIR (a folder or one file: Roof-Image *.polyshape, or real LoD2 city models in
CityJSON *.city.json/*.json, CityJSONSeq *.jsonl, CityGML *.gml/*.gml.gz, see dataset/README.md) from a
ring of oblique views (or from the street: --capture), detects 2D
segments (LSD), triangulates a 3D line cloud across the views and labels each 3D segment (f, i1, d1, i2,
d2) against the GT wireframe. Writes OUT/clouds/<name>.lcloud, OUT/status/<name>.json and a summary
(OUT/summary.json, or OUT/summary-shard-<i>-of-<n>.json). Finished buildings are skipped on re-runs.

options:
  -o, --out OUT               output folder
  --lod L                     city models: the LoD 2.x to read (2.2, 2.1, or 2 = 2.0; default: each
                              building's highest); buildings without it are not listed
  --renderer raster|blender   built-in software rasteriser (default) or Blender 3.4
  --views N                   views per building (default 20)
  --capture KIND              where the cameras stand: orbit (default: rings of oblique views all around,
                              20-45 degrees up, like a drone), street-1 (every view in a 90 degree sector
                              in front of one long facade), street-2 (a 180 degree sector around one
                              corner: two facades) or walk (street-1's views on one straight line along
                              the facade, 1.5-1.8 m up, as a pedestrian walking down the street); street
                              views from 1.5-3 m above the ground, looking at the building's centre, as
                              far back as it takes to frame the building.
                              The facade or corner comes from the seed; recorded in the summary and
                              status; a building done with another capture is rendered again
  --size WxH                  image size (default 640x480)
  --max-metres-per-pixel M    larger buildings get larger images (same framing, finer pixels): each
                              building's images grow until its bounding-box diagonal takes at most M metres
                              per pixel of width (default 0.05; 0 = --size for every building); LSD's
                              shortest segment and segment count follow; recorded as image_size in status/;
                              a building done with another value is rendered again
  --max-image-side N          the longest image side --max-metres-per-pixel may reach (default 4096)
  -j, --threads N             worker threads (default: all cores)
  --shard i/n                 process buildings k with k % n == i (for Slurm arrays, GNU parallel)
  --limit K                   at most K buildings of the shard
  --names FILE                only the buildings named in FILE, one per line (e.g. configs/splits/lod2/val.txt);
                              a name that --meshes does not hold is an error
  --seed S                    cameras, textures and noise (default 0)
  --keep-views                keep renders, cameras.json and views.json (projected GT with visibility)
  --supersample N             rasteriser samples per pixel side (default 1)
  --blur SIGMA                rasteriser optical blur in pixels (default 1.0; 0 = none)
  --view-light F              rasteriser, paper textures: share of the ambient light that dims with the angle
                              to the camera, so walls in the sun's shade differ and their corners show (0-1,
                              default 0.8; 0 = constant ambient, as renders before 2026-12-06); sfm and photo
                              textures keep a view-independent light, which structure from motion needs
  --no-shadows                no cast shadows
  --engine NAME               Blender engine: BLENDER_WORKBENCH (default), BLENDER_EEVEE, CYCLES
  --samples N                 Blender anti-aliasing / render samples (default 1 = no AA; Workbench 5 = anti-aliased)
  --textures paper|sfm|photo  paper-like textures (default), non-repeating noise for structure
                              from motion (lc2wf-colmap-poses on the kept views), or photo-like scenes:
                              windows and doors by storey, roof tiles, gutters, balconies, chimneys,
                              a road with cars, trees, neighbouring buildings (clutter: never GT), a
                              sun per building, per-view exposure, noise and blur
  --photo-without LIST        photo elements left out, comma-separated: windows, doors, balconies,
                              tiles, gutters, chimneys, ground, trees, neighbours, sun (fixed sun),
                              exposure, noise, blur (per-view changes)
  --photo-storey M            target storey height of the photo facades in metres (default 3; each
                              wall holds a whole number of storeys)
  --photo-exposure STOPS      per-view exposure change of photo renders, +-STOPS (default 0.5)
  --blender PATH              Blender executable (default: blender on PATH)
  --blender-batch N           buildings per Blender process (default 16)
  --lsd-min-length F          min 2D segment length, fraction of the image diagonal (default 0.005)
  --lsd-scale S               LSD's Gaussian pre-scaling of the image (default 0.8)
  --max-segments N            longest 2D segments kept per view (default 1000)
  --lsd-refine std|adv        LSD refinement (default std; adv drops many segments on clean renders)
  --min-score S               min cross-view score of a 3D line (default 0.75; 1.0 = two confirming views)
  --neighbours N              visual neighbours matched per view (default 10)
  --label-min-views N         f=1 needs votes for the same GT edge from N distinct support views (default 3)
  --min-ray-plane-angle DEG   a source ray this close to the target segment's plane gives no hypothesis (default 1)
  --endpoint-angle DEG        a segment this close to its epipolar line is matched by its endpoints (default 2;
                              0: never, as Line3D++)
  --neighbour-max-angle DEG   widest triangulation angle of a neighbour at the scene centre (default 60)
  --sigma-p PX                positional regulariser of the scoring, pixels (default 2.5)
  -q, --quiet                 no progress bar
The summary (JSON) goes to stdout. Exit code 1: some buildings failed (each named with its reason on stderr,
also with -q, and in the summary and OUT/status/); 3: no building to process (an empty mesh folder or shard)
or a fatal error.
)";

using lc2wf::UsageError;

std::pair<int, int> split_pair(const std::string& flag, const std::string& v, char sep) {
  const size_t p = v.find(sep);
  if (p == std::string::npos) throw UsageError(flag + " expects A" + sep + "B, got '" + v + "'");
  return {lc2wf::int_flag(flag, v.substr(0, p)), lc2wf::int_flag(flag, v.substr(p + 1))};
}

// --photo-without: each named element off; an unknown name is a usage error naming the flag.
void leave_out_photo_elements(const std::string& flag, const std::string& list, lc2wf::PhotoOptions& p) {
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const std::string e = list.substr(start, end - start);
    if (e == "windows") p.facades.windows = false;
    else if (e == "doors") p.facades.doors = false;
    else if (e == "balconies") p.balconies = false;
    else if (e == "tiles") p.roof_tiles = false;
    else if (e == "gutters") p.gutters = false;
    else if (e == "chimneys") p.chimneys = false;
    else if (e == "ground") p.ground = false;
    else if (e == "trees") p.trees = false;
    else if (e == "neighbours") p.neighbours = false;
    else if (e == "sun") p.vary_sun = false;
    else if (e == "exposure") p.exposure_stops = 0;
    else if (e == "noise") p.noise_gain = 1;
    else if (e == "blur") p.blur_gain = 1;
    else
      throw UsageError(flag + ": unknown element '" + e + "' (windows, doors, balconies, tiles, gutters, chimneys, ground, trees, "
                       "neighbours, sun, exposure, noise, blur)");
    start = end + 1;
  }
}

lc2wf::DatasetRunOptions parse_args(int argc, char** argv) {
  lc2wf::DatasetRunOptions o;
  o.command_line.assign(argv, argv + argc);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] { return lc2wf::flag_value(argc, argv, i); };
    if (a == "--meshes") {
      o.meshes = value();
    } else if (a == "--lod") {
      o.sources.lod = value();
    } else if (a == "-o" || a == "--out") {
      o.out = value();
    } else if (a == "--renderer") {
      const std::string r = value();
      if (r == "raster") o.renderer = lc2wf::RendererKind::Raster;
      else if (r == "blender") o.renderer = lc2wf::RendererKind::Blender;
      else throw UsageError("--renderer must be raster or blender, got '" + r + "'");
    } else if (a == "--views") {
      o.cameras.views = lc2wf::int_flag(a, value());
    } else if (a == "--capture") {
      o.capture = value();
    } else if (a == "--size") {
      std::tie(o.cameras.width, o.cameras.height) = split_pair(a, value(), 'x');
    } else if (a == "--max-metres-per-pixel") {
      o.max_metres_per_pixel = lc2wf::number_flag(a, value());
    } else if (a == "--max-image-side") {
      o.max_image_side = lc2wf::int_flag(a, value());
    } else if (a == "-j" || a == "--threads") {
      o.threads = lc2wf::threads_flag(a, value());
    } else if (a == "--shard") {
      std::tie(o.shard_index, o.shard_count) = split_pair(a, value(), '/');
    } else if (a == "--limit") {
      o.limit = lc2wf::int_flag(a, value());
    } else if (a == "--names") {
      o.names = value();
    } else if (a == "--seed") {
      o.seed = static_cast<uint64_t>(lc2wf::parse_count_flag(a, value()));
    } else if (a == "--keep-views") {
      o.keep_views = true;
    } else if (a == "--supersample") {
      o.raster.supersample = lc2wf::int_flag(a, value());
    } else if (a == "--blur") {
      o.raster.blur_sigma_px = lc2wf::number_flag(a, value());
    } else if (a == "--view-light") {
      o.raster.view_light = lc2wf::number_flag(a, value());
    } else if (a == "--no-shadows") {
      o.raster.shadows = false;
      o.blender.shadows = false;
    } else if (a == "--engine") {
      o.blender.engine = value();
    } else if (a == "--samples") {
      o.blender.samples = lc2wf::int_flag(a, value());
    } else if (a == "--textures") {
      o.blender.textures = o.raster.textures = value();
      if (o.blender.textures != "paper" && o.blender.textures != "sfm" && o.blender.textures != "photo")
        throw UsageError("--textures must be paper, sfm or photo, got '" + o.blender.textures + "'");
    } else if (a == "--photo-without") {
      leave_out_photo_elements(a, value(), o.photo);
    } else if (a == "--photo-storey") {
      o.photo.facades.storey_height_m = lc2wf::number_flag(a, value());
    } else if (a == "--photo-exposure") {
      o.photo.exposure_stops = lc2wf::number_flag(a, value());
    } else if (a == "--blender") {
      o.blender.executable = value();
    } else if (a == "--blender-batch") {
      o.blender_batch = lc2wf::int_flag(a, value());
    } else if (a == "--lsd-min-length") {
      o.cloud.lsd.min_length_frac = lc2wf::number_flag(a, value());
    } else if (a == "--lsd-refine") {
      const std::string r = value();
      if (r != "std" && r != "adv") throw UsageError("--lsd-refine must be std or adv, got '" + r + "'");
      o.cloud.lsd.refine_advanced = r == "adv";
    } else if (a == "--lsd-scale") {
      o.cloud.lsd.scale = lc2wf::number_flag(a, value());
    } else if (a == "--max-segments") {
      o.cloud.lsd.max_segments = lc2wf::int_flag(a, value());
    } else if (a == "--min-score") {
      o.cloud.triangulator.min_best_score = lc2wf::number_flag(a, value());
    } else if (a == "--neighbours") {
      o.cloud.triangulator.neighbours.count = lc2wf::int_flag(a, value());
    } else if (a == "--label-min-views") {
      o.cloud.labels.min_views = lc2wf::int_flag(a, value());
    } else if (a == "--min-ray-plane-angle") {
      o.cloud.triangulator.min_ray_plane_angle_deg = lc2wf::number_flag(a, value());
    } else if (a == "--endpoint-angle") {
      o.cloud.triangulator.endpoint_angle_deg = lc2wf::number_flag(a, value());
    } else if (a == "--neighbour-max-angle") {
      o.cloud.triangulator.neighbours.max_angle_deg = lc2wf::number_flag(a, value());
    } else if (a == "--sigma-p") {
      o.cloud.triangulator.sigma_p_px = lc2wf::number_flag(a, value());
    } else if (a == "-q" || a == "--quiet") {
      o.progress = false;
    } else {
      throw UsageError("unknown argument '" + a + "'");
    }
  }
  if (o.meshes.empty()) throw UsageError("--meshes DIR is required");
  if (o.out.empty()) throw UsageError("-o OUT is required");
  lc2wf::check_options([&] { o.Check(); }, {{"CameraRingOptions.views", "--views"},
                                            {"DatasetRunOptions.capture", "--capture"},
                                            {"CameraRingOptions.width/height", "--size"},
                                            {"DatasetRunOptions.max_metres_per_pixel", "--max-metres-per-pixel"},
                                            {"DatasetRunOptions.max_image_side", "--max-image-side"},
                                            {"RasterOptions.supersample", "--supersample"},
                                            {"RasterOptions.blur_sigma_px", "--blur"},
                                            {"RasterOptions.view_light", "--view-light"},
                                            {"BlenderOptions.engine", "--engine"},
                                            {"FacadeOptions.storey_height_m", "--photo-storey"},
                                            {"PhotoOptions.exposure_stops", "--photo-exposure"},
                                            {"BlenderOptions.samples", "--samples"},
                                            {"BlenderOptions.executable", "--blender"},
                                            {"DatasetRunOptions.blender_batch", "--blender-batch"},
                                            {"DatasetRunOptions.threads", "-j"},
                                            {"DatasetRunOptions.shard_index/shard_count", "--shard i/n"},
                                            {"DatasetRunOptions.limit", "--limit"},
                                            {"BuildingSourceOptions.lod", "--lod"},
                                            {"LsdOptions.min_length_frac", "--lsd-min-length"},
                                            {"LsdOptions.max_segments", "--max-segments"},
                                            {"LsdOptions.scale", "--lsd-scale"},
                                            {"TriangulatorOptions.min_best_score", "--min-score"},
                                            {"TriangulatorOptions.min_ray_plane_angle_deg", "--min-ray-plane-angle"},
                                            {"TriangulatorOptions.endpoint_angle_deg", "--endpoint-angle"},
                                            {"TriangulatorOptions.sigma_p_px", "--sigma-p"},
                                            {"NeighbourOptions.count", "--neighbours"},
                                            {"NeighbourOptions.min/max_angle_deg", "--neighbour-max-angle"},
                                            {"SupportLabelOptions.min_views", "--label-min-views"}});
  return o;
}

int run(const lc2wf::DatasetRunOptions& o) {
  const auto summary = lc2wf::run_dataset(o);
  std::cout << lc2wf::json_text(summary, 2) << std::endl;  // names need not be UTF-8
  // Every building left out, with its reason: -q silences the progress, not this.
  for (const auto& f : summary["failed"])
    std::fprintf(stderr, "lc2wf-dataset: skipped %s: %s\n", f["name"].get<std::string>().c_str(), f["error"].get<std::string>().c_str());
  return summary["failed"].empty() ? lc2wf::kExitDone : lc2wf::kExitPartly;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-dataset", kUsage,
                          {lc2wf::kEnvOmpThreads,
                           {"LC2WF_BLENDER_SCRIPT", "--renderer blender: the Blender script (default: tools/blender/render_building.py of the source tree)"}}},
                         argc, argv, parse_args, run);
}
