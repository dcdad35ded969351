// lc2wf-infer: line clouds -> predicted wireframes with a model trained by lc2wf-train.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/util/cli.h"
#include "infer/batch_inference.h"
#include "infer/post_process_flags.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-infer --weights DIR CLOUD... -o OUT [options]

Predicts a 3D wireframe for each line cloud: junction sampling -> junction model -> junction NMS and
confidence threshold -> all pairs -> edge model -> post-processing (identical-pair pruning, candidate
edges, isolated-edge removal, Hamming junction merge, line NMS, dangling-edge removal).
Writes OUT/<name>.obj (<name> = the cloud file's stem; 'v' + 'l', metres) and OUT/<name>.json (junction confidences, edge
probabilities and notes on degenerate inputs). A cloud with no usable junction or edge gives an empty
wireframe and a note, never a failure.

  --weights DIR       junction.safetensors + edge.safetensors written by lc2wf-train
  -o, --out OUT       output folder
  --units U           metres (default) or raw: coordinates of the written .obj (raw = the source
                      dataset's units, e.g. Roof-Image / release JSON, 20 raw = 1 m)
  --preview PNG       also draw cloud (grey), prediction (red) and GT (green, when the cloud has it);
                      with one cloud PNG is the file, with several it is a folder for <name>.png
  --release-quirks    post-process exactly as the paper's release (suppressor NMS, lower-confidence
                      edge kept by line NMS, no edge transfer on junction merge, no junction
                      refinement); default: sound rules
  --no-junction-refine  keep the regressed junction positions (default: each selected junction moves
                      to the meeting point of the cloud's segments ending within 0.5 m of it)
  --min-confidence C  junctions paired by the edge model: confidence > C (default 0.05; the release: 0.85)
  --pair-support S    classify only pairs of junctions whose straight line is covered by the cloud's
                      segments for at least S of its length (0-1; segments within 0.35 m and 20 degrees
                      of it; pairs shorter than 1 m always); default 0 = every pair, as the release
  --edge-support S    after post-processing keep only edges the cloud's segments cover for at least S
                      of their length (0-1; segments within 0.35 m and 20 degrees of it) or, with
                      --edge-cameras N, that N of the cloud's cameras had in view; junctions left without
                      an edge go: nothing is drawn that no line shows. Applied when the cloud's cameras
                      leave a side of the building unseen (default 0.85; 0 keeps every edge, as the
                      release)
  --edge-support-everywhere  apply --edge-support to every cloud, also full orbits and clouds without cameras
  --judge-degree-above N  elsewhere, still keep only the edges of junctions with more than N edges that
                      lines cover for at least 0.2 of their length, where the edge model accepted a
                      near-complete subgraph (default 8; 0 = never)
  --crossing-distance M  of two edges that pass within M metres of each other away from their ends (a
                      building's edges meet only at junctions), keep the higher-scoring one (default 0.25;
                      0 = keep both)
  --drop-flat-parts N where the cloud's cameras leave a side unseen, drop the parts of the wireframe other
                      than the longest that have fewer than N edges and lie within 0.75 m of one plane:
                      window frames, doors, a neighbour's face in photo clouds (default 0 = keep them;
                      lc2wf-reconstruct: 10)
  --edge-cameras N    also keep an edge without line support when N cameras had it in view (in front,
                      inside the image, not behind the block over the wireframe's footprint): for clean
                      clouds whose low-contrast edges draw no line (default 0 = the lines alone decide)
  --max-pairs N       at most N junction pairs go to the edge model (default 1280; 0 = no cap): above N,
                      the pairs with the most line support within 2 m of their junctions, each junction in
                      at most --max-pairs-per-junction K of them (default 64), so the edge model's time
                      stays bounded however cluttered the cloud; a note says when it bites
  --nms-radius M      candidate junctions closer than M metres to a more confident one are dropped
                      before the cut (default 0.5; the release: 0.25)
  --max-offset M      ignore candidate junctions regressed more than M metres from their patch's sample
                      point (default 0.75; 0 = every candidate, as the release)
  --corner-radius M   keep a selected junction only where the cloud's segments ending within M metres of
                      it run in two directions at least 20 degrees apart: a corner, not the middle of an
                      edge (default 0.3; 0 = every junction, as the release)
  --footing-radius M  keep a selected junction on the cloud's ground level only where segment ends at
                      least 1 m higher lie within M metres of it horizontally: a wall stands on it, not a
                      cast shadow's or a path's corner (default 0.3; 0 = every junction, as the release)
                      --release-quirks selects as the release (0.85, 0.25, every candidate); how the
                      defaults were chosen and what they score: infer/README.md
  --sampling-passes N run the junction model on N x 256 sample points, 256 at a time (default 1, the
                      release): more GT junctions get a sample point near them, and more candidates
                      are paired
  --metres-per-pass M at least one pass per M metres of the cloud's longer horizontal side (2nd-98th
                      percentile of its endpoints), at most 8, so a large building gets sample points for
                      its size (default 40; 0 = only --sampling-passes)
  --density-seeds S   which segment endpoints seed the sample points before the farthest-point
                      sampling: loose (default: more than 4 endpoints within 0.3 m, one seed per 0.3 m),
                      release (more than 12, one per 0.075 m; --release-quirks) or MIN_COUNT,MIN_RATIO,
                      NMS_M
  --test-time-views N each junction candidate is the model's mean answer over N views of its patch (1, 2,
                      4 or 8: turned by quarter turns or mirrored about the vertical; default 1, the
                      release); the junction model runs N times
  --edge-test-time-views N  the same for the edge model: each pair's class probabilities are the mean over
                      N views (1, 2, 4 or 8; default 1); the edge model runs N times
  --max-segment-length M|auto  cut segments longer than M metres into two staggered chains of pieces
                      before inference, as the per-view fragments the model was trained on (0 = never,
                      0.05-100: every cloud). Default auto: 1.5 m, only clouds read from Line3D++, LIMAP or
                      OBJ files whose lines merge the views' fragments (under 0.7 of their lines longer
                      than 1.5 m overlapped by another line); our files are never cut.
                      A cut cloud is sampled in at least 3 passes (--sampling-passes), since its corners
                      hold fewer endpoints
  --format F          auto (default), lc2wf, release (LineCloud JSON), line3dpp (Line3D++ .txt),
                      limap (a finaltracks/ folder) or obj (line OBJ of Line3D++/LIMAP); detected from
                      the content (folder = LIMAP, .obj = line OBJ)
  --frame F           auto (default) or as-read: how a line map made elsewhere (Line3D++, LIMAP, OBJ; not
                      our files, which are metric and z up) is put in the networks' frame (metres, z up,
                      ground at 0). auto: up from the lines' dominant directions and the normals of
                      their pairs: the one under which the lines' statistics look most like the height
                      model's training clouds of buildings the right way up, and the end its nearest
                      clouds say is the ground at the bottom, with a warning when another direction looks
                      almost as upright (without a height model: the direction most lines are
                      perpendicular to, the widest structure at the bottom), refined by
                      the near-vertical lines; ground at the lowest structure; scale from --scale,
                      --known-distance or --building-height, the facades' storeys (the heights the
                      short vertical lines - window and door sides - cover repeat once per storey of
                      --storey-height metres), the height the weights' height model reads from the
                      lengths and directions of the lines (--height-model), else the scale search (the
                      networks run on the map at building heights of 3-60 m, the most confident
                      wireframe wins). The wireframe is written in that frame and
                      OUT/<name>.frame.json holds the similarity from the map, the up and scale found,
                      where they came from and the search's scores. as-read: the map's coordinates are
                      taken as metres, z up
  --up U              the map's up: an axis x, y, z, -x, -y or -z, or a direction X,Y,Z in the map's
                      frame, e.g. a gravity vector from the survey (default auto)
  --scale F           metres per map unit
  --known-distance X1,Y1,Z1,X2,Y2,Z2,D  two points of the map (map units) are D metres apart
  --building-height M the building's height above its ground, metres
  --storey-height M   floor-to-floor height of the building's storeys, metres (default 3; old city houses
                      and offices 3.5-4); 0 skips the storey estimate
  --height-model FILE|none  the height model (lc2wf-fit-height) that scales a map nothing before it
                      scales (default: height.json in the --weights folder when there is one; none
                      leaves such maps to the scale search)
  --scale-measure M   what the scale search maximises: edge-confidence (default: the mean over the kept
                      edges of P(edge) x the geometric mean of their junctions' confidences),
                      edge-evidence (the sum over the kept edges of P(edge) x both confidences),
                      confident-junctions or junction-mean (reconstruct/README.md, "Scale search")
  --precision P       fp32 (default: the same numbers at any thread count; CPUs whose matrix kernels
                      differ, AVX2 or AVX-512, differ in the last bits), bf16 (operands rounded to bf16,
                      fp32 sums; fast where the CPU has AVX512-BF16, emulated elsewhere) or auto
                      (bf16 where it has, else fp32)
  --no-surfaces       do not write the LoD2 surfaces: by default OUT/<name>.city.json (CityJSON 2.0, one
                      Building: a Solid when the faces close, else a MultiSurface; roof / wall / ground
                      semantics; same frame and units as OUT/<name>.obj) and OUT/<name>.faces.obj (one
                      polygon per face, groups roof, wall, ground) are written beside each wireframe
  -j, --threads N     compute threads (default: all cores)
  -q, --quiet         no progress output
Each written OUT/<name>.obj is printed on stdout. Exit code 1: some clouds could not be read or predicted
(each is named), 3: none could, or the weights are missing.
)";

double positive_flag(const std::string& flag, const std::string& value) {
  const double x = number_flag(flag, value);
  if (!(x > 0)) throw UsageError(flag + " must be > 0, got '" + value + "'");
  return x;
}

struct Args {
  fs::path weights, out;
  std::string preview;
  std::string height_model;  // --height-model: "none", a file, or empty (the weights folder's height.json)
  std::vector<fs::path> clouds;
  BatchInferenceOptions options;
  PostProcessFlags post;
  int threads = 0;
  bool surfaces = true;  // --no-surfaces
};

Args parse_args(int argc, char** argv) {
  Args a;
  a.options.map_frame.enabled = true;  // --frame auto
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    if (f == "--weights") a.weights = value();
    else if (f == "-o" || f == "--out") a.out = value();
    else if (f == "--preview") a.preview = value();
    else if (a.post.parse(f, argc, argv, i)) continue;
    else if (f == "-q" || f == "--quiet") a.options.quiet = true;
    else if (f == "--no-surfaces") a.surfaces = false;
    else if (f == "--frame") {
      const std::string v = value();
      if (v != "auto" && v != "as-read") throw UsageError("--frame must be auto or as-read, got '" + v + "'");
      a.options.map_frame.enabled = v == "auto";
    } else if (f == "--up") a.options.map_frame.up = value();
    else if (f == "--scale") a.options.map_frame.scale = positive_flag(f, value());
    else if (f == "--building-height") a.options.map_frame.building_height_m = positive_flag(f, value());
    else if (f == "--height-model") {
      a.height_model = value();
      if (a.height_model.empty()) throw UsageError("--height-model needs a file or 'none'");
    }
    else if (f == "--storey-height") {
      a.options.map_frame.storeys.storey_height_m = number_flag(f, value());
      if (!(a.options.map_frame.storeys.storey_height_m >= 0 && a.options.map_frame.storeys.storey_height_m <= 20))
        throw UsageError("--storey-height must be in [0, 20]");
    }
    else if (f == "--scale-measure") {
      try {
        a.options.map_frame.search.measure = parse_scale_measure(value());
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--scale-measure: ") + e.what());
      }
    } else if (f == "--known-distance") {
      const std::string v = value();
      double p[7];
      char tail;
      if (std::sscanf(v.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf%c", &p[0], &p[1], &p[2], &p[3], &p[4], &p[5], &p[6], &tail) != 7 ||
          !Eigen::Matrix<double, 7, 1>(p).allFinite() || !(p[6] > 0) || Vec3(p[0] - p[3], p[1] - p[4], p[2] - p[5]).norm() == 0)
        throw UsageError("--known-distance expects X1,Y1,Z1,X2,Y2,Z2,METRES (two different points, a distance > 0), got '" + v + "'");
      a.options.map_frame.known_a = Vec3(p[0], p[1], p[2]);
      a.options.map_frame.known_b = Vec3(p[3], p[4], p[5]);
      a.options.map_frame.known_distance_m = p[6];
    }
    else if (f == "--precision") a.options.precision = precision_flag(value());
    else if (f == "--format") {
      try {
        a.options.format = parse_cloud_format(value(), "--format");
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    } else if (f == "-j" || f == "--threads") {
      a.threads = threads_flag(f, value());
    } else if (f == "--units") {
      const std::string u = value();
      if (u == "raw") a.options.raw_units = true;
      else if (u != "metres" && u != "meters") throw UsageError("--units must be 'metres' or 'raw', got '" + u + "'");
    } else if (!f.empty() && f[0] == '-') {
      throw UsageError("unknown option '" + f + "'");
    } else {
      a.clouds.push_back(f);
    }
  }
  if (a.weights.empty()) throw UsageError("--weights DIR is required");
  if (a.out.empty()) throw UsageError("-o OUT is required");
  if (a.clouds.empty()) throw UsageError("no line cloud given");
  a.options.post = a.post.options();
  check_options([&] { a.options.map_frame.Check(); }, {{"MapFrameOptions.up", "--up"}});
  a.options.write_surfaces = a.surfaces;
  if (!a.preview.empty()) {
    const fs::path p = a.preview;
    if (a.clouds.size() == 1) a.options.preview_path = [p](const std::string&) { return p; };
    else a.options.preview_path = [p](const std::string& name) { return p / (name + ".png"); };
  }
  return a;
}

int run(const Args& a) {
  set_num_threads(a.threads);
  BatchInferenceOptions options = a.options;
  options.map_frame.height_model = choose_height_model(a.height_model, a.weights);  // a small file: checked first
  const WireframePredictor predictor(a.weights);
  const BatchInferenceSummary s = infer_clouds(predictor, a.clouds, a.out, options);
  for (const std::string& name : s.names) std::printf("%s\n", (a.out / (name + ".obj")).string().c_str());
  if (!a.options.quiet && a.surfaces && s.buildings > 0)
    std::fprintf(stderr, "lc2wf-infer: surfaces: %d of %d closed solid(s); %.2f ms per building\n", s.closed_solids, s.buildings,
                 1000 * s.surface_seconds / s.buildings);
  if (!a.options.quiet && s.framed > 0)
    std::fprintf(stderr, "lc2wf-infer: %d map(s) put in the networks' frame (OUT/<name>.frame.json); %.2f s per map, frame and inference\n",
                 s.framed, s.frame_seconds / s.framed);
  if (!a.options.quiet && s.buildings > 0)
    std::fprintf(stderr,
                 "lc2wf-infer: %d building(s) -> %s (%d empty); %.3f s per building on average (junction %.3f, "
                 "edge %.3f, post-processing %.3f), max %.3f s\n",
                 s.buildings, a.out.string().c_str(), s.empty, s.total_seconds / s.buildings,
                 s.junction_seconds / s.buildings, s.edge_seconds / s.buildings, s.post_seconds / s.buildings,
                 s.max_seconds);
  return s.failed == 0 ? kExitDone : s.buildings > 0 ? kExitPartly : kExitDataError;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-infer", kUsage, {kEnvOmpThreads, kEnvStorageCache, kEnvGemm}}, argc, argv, parse_args, run);
}
