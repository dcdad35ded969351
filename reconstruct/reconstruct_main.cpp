// lc2wf-reconstruct: a folder of photos -> a 3D wireframe (cameras, LSD, triangulation, metric frame,
// inference, post-processing), with the line cloud, a preview and a JSON report.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "core/util/cli.h"
#include "dataset/formats/errors.h"
#include "infer/post_process_flags.h"
#include "reconstruct/reconstruct_pipeline.h"
#include "reconstruct/stage_error.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-reconstruct IMAGES_DIR --weights DIR -o OUT [options]

Photos of one building -> 3D wireframe. Stages (progress on stderr): weights, images (*.jpg, *.png, *.tif,
*.bmp of IMAGES_DIR in name order, one camera per image size; HEIC and raw files are named, not read),
cameras (COLMAP 3.8 on the CPU, or --cameras), lsd (2D segments), triangulation (our multi-view line
triangulation), frame (scale, up, ground), confirmation (lines no other view confirms dropped), inference
(junction and edge models), outputs. OUT receives, only when
every stage succeeded:
  wireframe.obj + wireframe.json   the wireframe (metres, z up) and its scores
  cloud.lcloud, cloud.obj          the confirmed line cloud inference ran on (our format; OBJ for MeshLab)
  cameras.json                     the cameras in the output frame (null = not registered)
  preview.png                      cloud (grey) and wireframe (red)
  report.json                      images registered, segments, 3D lines (those matched by their endpoints,
                                   and the unconfirmed ones), junctions, edges, the frame and the seconds
                                   of every stage

Frame. COLMAP's frame has no metric scale and an arbitrary up axis; the networks expect metres, z up,
ground at z = 0:
  up      the GPS frame's up when the scale came from GPS, else the mean of the cameras' up vectors
          (photos are taken upright); refined by the dominant direction of the 3D lines within 15 deg
          of it (vertical wall corners) when >= 10 such lines exist; --up z keeps the input z axis,
          --up X,Y,Z gives it
  scale   from evidence, the first there is: --scale F (metres per COLMAP unit); --known-distance
          A,B,D (the camera centres of images A and B are D metres apart); the photos' EXIF GPS
          (>= 3 registered photos with position and altitude, not on one line: the camera centres
          are fitted to them, which also gives up and north; --no-gps ignores it); --building-height
          M (the cloud's height above its ground, the 99th - 1st percentile of the endpoint heights,
          is M metres); the facades' storeys (the heights the short vertical lines - window and
          door sides - cover repeat once per storey; a storey is --storey-height metres); the height the
          weights' height model reads from the lengths and directions of the lines (windows, doors
          and eaves have sizes of their own; --height-model); else the scale search: the networks run
          on the cloud at building heights of 3-60 m and the most confident wireframe wins
          (report.json: its scores per height)
  origin  x/y at the median segment midpoint, z = 0 at the 1st percentile of endpoint heights
Up, height and origin are measured on the best-supported lines (>= k supporting 2D segments, k the
largest up to 8 that leaves >= 100 lines), so texture clutter above the roof and below the ground does
not bias them.
With --cameras FILE.json (the project's cameras: metres, z up) the frame is kept: up z, scale 1.

Options:
  --weights DIR          junction.safetensors + edge.safetensors written by lc2wf-train (required;
                         models/general for real buildings of any roof kind and height; models/README.md)
  -o, --out OUT          output folder (created; other files in it are left alone)
  --cameras PATH         known cameras instead of COLMAP: a COLMAP model folder (cameras/images .txt
                         or .bin, matched by image name) or a cameras JSON (one entry or null per image)
  --intrinsics fx,fy,cx,cy  COLMAP intrinsics (OpenCV convention: pixel (0,0) = centre of top-left pixel;
                         photos of one size)
  --focal-35mm F         else fx = fy = F / 36 x the longer side of each photo, F the 35 mm-equivalent focal
                         length (default: each photo's EXIF, FocalLengthIn35mmFilm or FocalLength over the
                         sensor size; without it 35, refined by COLMAP's bundle adjustment)
  --max-features N       SIFT features per image (default 2000)
  --first-octave N       SIFT's first octave: -1 the image doubled first, 0 at its own size (fewer, larger
                         features found in less time); default -1 for photos within --max-image-side, 0
                         for larger ones (SIFT scales them down first)
  --max-image-side N     SIFT and LSD see each photo scaled down to at most N pixels on its longer side
                         (default 1600; their points stay in full-size pixels), so large photos cost
                         about what 2 MP ones do
  --matcher M            exhaustive (default) or sequential (photos taken in order)
  --init-min-inliers N   COLMAP mapper: verified matches the initial pair needs (default 100; lower it
                         when the mapper finds no initial pair)
  --abs-pose-min-inliers N  COLMAP mapper: 2D-3D inliers a view needs to be registered (default 30)
  --min-score S          triangulation: a 2D segment's best hypothesis needs a score above S (sum of
                         the agreeing views' similarities; default 0.75 as lc2wf-dataset, 1.0 = two
                         confirming views)
  --endpoint-angle DEG   triangulation: a segment this close to its epipolar line (a facade's horizontals
                         photographed walking along it) is matched by its endpoints (default 2; 0: never)
  --min-confirming-views K  keep a 3D line only when lines triangulated from >= K other views overlap
                         it (default 1; 0 keeps every line): most lone lines of a textured scene are
                         chance matches floating above the roof (reconstruct/README.md)
  --up U                 auto (default), cameras (no line refinement), z, or X,Y,Z
  --scale F              metres per input unit
  --known-distance A,B,D camera centres of images A and B (file names) are D metres apart
  --building-height M    the building's height above its ground, metres (used when no known
                         distance or GPS gives the scale)
  --storey-height M      floor-to-floor height of the building's storeys, metres (default 3; old city
                         houses and offices 3.5-4); 0 skips the storey estimate
  --height-model FILE|none  the height model (lc2wf-fit-height) that scales the cloud when nothing before
                         it does (default: height.json in the --weights folder when there is one; none
                         leaves such clouds to the scale search)
  --no-gps               do not take scale and up from the photos' EXIF GPS
  --reference-cameras F  evaluation: also write wireframe_aligned.obj in the frame of these cameras
                         (cameras JSON, one per image; similarity fitted on the camera centres)
  --release-quirks       post-process as the paper's release (see lc2wf-infer --help)
  --no-junction-refine   keep the regressed junction positions (see lc2wf-infer --help)
  --min-confidence C     junctions paired by the edge model: confidence > C (default 0.05)
  --pair-support S       classify only pairs with line support >= S (0-1; see lc2wf-infer --help)
  --edge-support S       keep only edges covered by the cloud's segments for >= S of their length or seen
                         by --edge-cameras cameras (0-1; default 0.85; 0 keeps every edge; see lc2wf-infer --help)
  --edge-cameras N       also keep an edge without line support that N cameras had in view (default 0: the
                         lines alone decide)
  --edge-support-everywhere  the default here: photo clouds are judged on every capture
  --drop-flat-parts N    drop the parts of the wireframe other than the longest that have fewer than N edges
                         and lie within 0.75 m of one plane: window frames, doors, a neighbour's face (default
                         10, on every capture here; 0 = keep them)
  --judge-degree-above N  otherwise still to the edges of junctions with more than N edges (see lc2wf-infer --help)
  --crossing-distance M  of two edges crossing within M metres, keep the higher-scoring one (default 0.25;
                         0 = keep both; see lc2wf-infer --help)
  --max-pairs N          at most N pairs for the edge model (default 1280; see lc2wf-infer --help)
  --max-pairs-per-junction K  and at most K per junction when the cap bites (default 64)
  --nms-radius M         point-NMS radius of the candidate junctions (default 0.5 m; see lc2wf-infer --help)
  --max-offset M         ignore candidates regressed more than M metres from their sample point (default 0.75;
                         0 = every candidate; see lc2wf-infer --help)
  --corner-radius M      keep junctions where segments of two directions end within M metres (default 0.3;
                         0 = every junction; see lc2wf-infer --help)
  --footing-radius M     keep ground junctions only where lines rise within M metres of them (default 0.3;
                         0 = every junction; see lc2wf-infer --help)
  --sampling-passes N    the junction model's sample points in N passes of 256 (default 1; see lc2wf-infer --help)
  --metres-per-pass M    at least one pass per M metres of the cloud's longer side (default 40; 0 = off)
  --density-seeds S      which endpoints seed the sample points: loose (default), release or
                         MIN_COUNT,MIN_RATIO,NMS_M (see lc2wf-infer --help)
  --test-time-views N    the junction model's mean over N views of each patch (default 4 here: photo clouds;
                         see lc2wf-infer --help)
  --edge-test-time-views N  the edge model's mean over N views of the pairs (default 1; see lc2wf-infer --help)
  --max-segment-length M|auto  cut segments longer than M metres into pieces first (default auto: merged
                         Line3D++/LIMAP maps only; our triangulation's clouds are not cut; see lc2wf-infer --help)
  --workspace DIR        intermediate files there (must be new or empty; never deleted)
  --keep                 keep the private temporary workspace (its path is printed)
  --no-surfaces          do not write the LoD2 surfaces wireframe.city.json (CityJSON 2.0) and
                         wireframe.faces.obj (polygons grouped roof / wall / ground) beside wireframe.obj
  -j, --threads N        threads for COLMAP, triangulation and the networks (default: all cores)
  -q, --quiet            no progress output
Exit code 1: done, but some images were unreadable or not registered, or the wireframe is empty (see
"warnings" in report.json); 3: too few images, too few registered, no 2D or 3D lines, unreadable weights
or cameras, or an I/O error (the message names the stage and the files, and nothing is written to OUT).
)";

Vec3 parse_vector(const std::string& flag, const std::string& value) {
  const std::optional<Vec3> v = parse_xyz(value);
  if (!v) throw UsageError(flag + " expects finite X,Y,Z, got '" + value + "'");
  return *v;
}

ReconstructOptions parse_args(int argc, char** argv) {
  ReconstructOptions o;
  PostProcessFlags post;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    if (f == "--weights") o.weights = value();
    else if (f == "-o" || f == "--out") o.out = value();
    else if (f == "--cameras") o.cameras = value();
    else if (f == "--reference-cameras") o.reference_cameras = value();
    else if (f == "--workspace") o.workspace = value();
    else if (f == "--keep") o.keep = true;
    else if (f == "--no-surfaces") o.surfaces = false;
    else if (f == "--no-gps") o.use_gps = false;
    else if (f == "--building-height") {
      o.frame.building_height_m = number_flag(f, value());
      if (!(o.frame.building_height_m > 0)) throw UsageError("--building-height must be > 0");
    }
    else if (f == "--height-model") {
      o.height_model = value();
      if (o.height_model.empty()) throw UsageError("--height-model needs a file or 'none'");
    }
    else if (f == "--storey-height") {
      o.frame.storeys.storey_height_m = number_flag(f, value());
      if (!(o.frame.storeys.storey_height_m >= 0 && o.frame.storeys.storey_height_m <= 20)) throw UsageError("--storey-height must be in [0, 20]");
    }
    else if (f == "-q" || f == "--quiet") o.quiet = true;
    else if (f == "-j" || f == "--threads") o.threads = threads_flag(f, value());
    else if (post.parse(f, argc, argv, i)) continue;
    else if (f == "--focal-35mm") o.focal_35mm = number_flag(f, value());
    else if (f == "--max-features") o.colmap.max_features = int_flag(f, value());
    else if (f == "--first-octave") o.colmap.first_octave = int_flag(f, value());
    else if (f == "--max-image-side") o.colmap.max_image_size = o.lsd.max_side = int_flag(f, value());
    else if (f == "--matcher") o.colmap.matcher = value();
    else if (f == "--init-min-inliers") o.colmap.init_min_inliers = int_flag(f, value());
    else if (f == "--abs-pose-min-inliers") o.colmap.abs_pose_min_inliers = int_flag(f, value());
    else if (f == "--min-score") o.triangulator.min_best_score = number_flag(f, value());
    else if (f == "--endpoint-angle") o.triangulator.endpoint_angle_deg = number_flag(f, value());
    else if (f == "--min-confirming-views") o.confirmation.min_other_views = int_flag(f, value());
    else if (f == "--scale") {
      o.frame.scale = number_flag(f, value());
      if (!(o.frame.scale > 0)) throw UsageError("--scale must be > 0");
      o.scale_given = true;
    } else if (f == "--intrinsics") {
      double fx, fy, cx, cy;
      char tail;
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%lf,%lf,%lf,%lf%c", &fx, &fy, &cx, &cy, &tail) != 4 || !Eigen::Vector4d(fx, fy, cx, cy).allFinite())
        throw UsageError("--intrinsics expects finite fx,fy,cx,cy, got '" + v + "'");
      o.intrinsics = Eigen::Vector4d(fx, fy, cx, cy);
    } else if (f == "--known-distance") {
      const std::string v = value();
      const size_t c1 = v.find(','), c2 = v.rfind(',');
      if (c1 == std::string::npos || c2 == c1) throw UsageError("--known-distance expects IMAGE_A,IMAGE_B,METRES, got '" + v + "'");
      o.known_image_a = v.substr(0, c1);
      o.known_image_b = v.substr(c1 + 1, c2 - c1 - 1);
      o.frame.known_distance_m = number_flag(f, v.substr(c2 + 1));
      if (!(o.frame.known_distance_m > 0)) throw UsageError("--known-distance: the distance must be > 0");
      o.scale_given = true;
    } else if (f == "--up") {
      const std::string v = value();
      o.up_given = true;
      if (v == "auto") o.frame.up = UpSource::kAuto;
      else if (v == "cameras") o.frame.up = UpSource::kCameras;
      else if (v == "z") o.frame.up = UpSource::kInputZ;
      else o.frame.up = UpSource::kGiven, o.frame.given_up = parse_vector(f, v);
      if (o.frame.up == UpSource::kGiven && !(o.frame.given_up.norm() > 0))
        throw UsageError("--up '" + v + "' is the zero vector: give a direction, e.g. 0,0,1");
    } else if (!f.empty() && f[0] == '-') {
      throw UsageError("unknown option '" + f + "'");
    } else if (o.images.empty()) {
      o.images = f;
    } else {
      throw UsageError("one image folder only, got '" + f + "' too");
    }
  }
  if (o.images.empty()) throw UsageError("IMAGES_DIR is required");
  if (o.weights.empty()) throw UsageError("--weights DIR is required");
  if (o.out.empty()) throw UsageError("-o OUT is required");
  o.post = post.options(ReconstructOptions{}.post);
  check_options([&] { o.Check(); }, {{"ReconstructOptions.focal_35mm", "--focal-35mm"},
                                     {"ReconstructOptions.intrinsics", "--intrinsics"},
                                     {"ReconstructOptions: a known distance", "--known-distance"},
                                     {"ColmapOptions.max_features", "--max-features"},
                                     {"ColmapOptions.first_octave", "--first-octave"},
                                     {"ColmapOptions.max_image_size", "--max-image-side"},
                                     {"ColmapOptions.matcher", "--matcher"},
                                     {"ColmapOptions.init_min_inliers", "--init-min-inliers"},
                                     {"ColmapOptions.abs_pose_min_inliers", "--abs-pose-min-inliers"},
                                     {"TriangulatorOptions.min_best_score", "--min-score"},
                                     {"TriangulatorOptions.endpoint_angle_deg", "--endpoint-angle"},
                                     {"LineConfirmationOptions.min_other_views", "--min-confirming-views"}});
  if (!fs::is_directory(o.images)) throw std::runtime_error("'" + o.images.string() + "' is not a folder");  // a data error
  return o;
}

int run(const ReconstructOptions& o) {
  try {
    const ReconstructResult r = reconstruct(o);
    for (const auto& w : r.warnings) std::fprintf(stderr, "lc2wf-reconstruct: warning: %s\n", w.c_str());
    return r.exit_code;
  } catch (const std::exception& e) {
    // StageError names its stage; other failures here are I/O (workspace, outputs).
    const bool staged = dynamic_cast<const StageError*>(&e) != nullptr;
    std::fprintf(stderr, "lc2wf-reconstruct: error: %s%s\nnothing was written to %s\n", staged ? "" : "I/O: ", e.what(), o.out.string().c_str());
    return kExitDataError;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return cli_main({"lc2wf-reconstruct", kUsage, {kEnvOmpThreads, kEnvStorageCache, kEnvGemm}}, argc, argv, parse_args, run);
}
