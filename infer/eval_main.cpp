// lc2wf-eval: scores predicted wireframes against ground truth (the paper's Table 2 metrics).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "core/util/input_file.h"
#include "core/util/progress.h"
#include "infer/post_process_flags.h"
#include "dataset/formats/building_sources.h"  // is_city_model_file_name, normalise_lod2, BuildingSkipped
#include "infer/eval_inputs.h"
#include "infer/eval_report_io.h"
#include "infer/building3d_io.h"
#include "model/evaluator.h"
#include "infer/html_report.h"
#include "infer/prediction_io.h"
#include "dataset/formats/cloud_input.h"
#if LC2WF_EVAL_WITH_WEIGHTS
#include "core/parallel.h"
#include "infer/batch_inference.h"
#endif

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

// The inference record of OUT/metrics.json when `pred` is OUT/predictions and the record covers as many
// buildings as are scored now; nothing otherwise (or when the file is unreadable: it is rewritten anyway).
std::optional<InferenceTiming> recorded_inference(const fs::path& out, const fs::path& pred, size_t buildings) {
  std::error_code ec;
  const fs::path metrics = out / "metrics.json";
  if (!fs::equivalent(pred, out / "predictions", ec) || !fs::is_regular_file(metrics, ec)) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_input_file(metrics));
    if (!j.contains("inference")) return std::nullopt;
    const InferenceTiming s = inference_from_json(j["inference"]);
    if (s.buildings == static_cast<int>(buildings)) return s;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

const char* kUsage = R"(Usage: lc2wf-eval --pred DIR (--gt DIR | --data DIR) -o OUT [options]
       lc2wf-eval --weights DIR --data DIR --split FILE -o OUT [options]

Scores predicted wireframes against the ground truth with the LC2WF paper's metrics (Table 2):
vAP/vRecall at eta = 0.15/0.25/0.35 m, sAP/sRecall at eta = 0.25/0.35/0.50 m (one ranked list pooled
over all buildings) and WED (mean per building), plus Building3D-style CP/CR/CF1, EP/ER/EF1, ACO and
B3D-nWED in a separate section, and the LoD2 surfaces found in each prediction (lc2wf-infer's .city.json)
scored against the GT mesh faces: roof-facet precision / recall, labels, valid closed solids, roof area
(Roof-Image polyshape GT only). See infer/README.md for the exact definitions.

  --pred DIR      predicted wireframes <name>.obj ('v' + 'l') with optional <name>.json scores
                  (junction_scores / edge_scores); without scores every score is 1
  --weights DIR   run inference first (junction.safetensors + edge.safetensors from lc2wf-train) on the
                  line clouds of --data; predictions go to OUT/predictions
  --release-quirks  with --weights: the release's post-processing instead of the sound rules
  --no-junction-refine  with --weights: keep the regressed junction positions (see lc2wf-infer --help)
  --min-confidence C  with --weights: junctions paired by the edge model have confidence > C (default 0.05)
  --pair-support S  with --weights: classify only pairs with line support >= S (see lc2wf-infer --help)
  --edge-support S, --edge-cameras N  with --weights: keep only edges with line support >= S or seen by N
                  cameras (default 0.85 and 0) where the cameras leave a side unseen; --edge-support-everywhere:
                  in every cloud; --judge-degree-above N: elsewhere at junctions of more than N edges;
                  --drop-flat-parts N: the small flat parts (see lc2wf-infer --help)
  --max-pairs N, --max-pairs-per-junction K  with --weights: the pair cap (see lc2wf-infer --help)
  --crossing-distance M  with --weights: of two crossing edges keep the higher-scoring one (default 0.25 m;
                  0 = keep both; see lc2wf-infer --help)
  --nms-radius M  with --weights: point-NMS radius of the candidate junctions (default 0.5 m)
  --max-offset M  with --weights: ignore candidates regressed more than M metres from their sample point
                  (default 0.75; 0 = every candidate; see lc2wf-infer --help)
  --corner-radius M  with --weights: keep junctions where segments of two directions end within M metres
                  (default 0.3; 0 = every junction; see lc2wf-infer --help)
  --footing-radius M  with --weights: keep ground junctions only where lines rise within M metres of them
                  (default 0.3; 0 = every junction; see lc2wf-infer --help)
  --sampling-passes N  with --weights: the junction model's sample points in N passes (default 1; see
                  lc2wf-infer --help)
  --metres-per-pass M  with --weights: at least one pass per M metres of a cloud's longer side (default 40;
                  0 = off; see lc2wf-infer --help)
  --density-seeds S  with --weights: which endpoints seed the sample points, loose (default), release or
                  MIN_COUNT,MIN_RATIO,NMS_M (see lc2wf-infer --help)
  --test-time-views N  with --weights: the junction model's mean over N views of each patch (default 1;
                  see lc2wf-infer --help)
  --edge-test-time-views N  with --weights: the edge model's mean over N views of the pairs (default 1)
  --max-segment-length M|auto  with --weights: cut segments longer than M metres into pieces first
                  (default auto: merged Line3D++/LIMAP/OBJ maps only; 0 = never; see lc2wf-infer --help)
  --previews      with --weights: also write OUT/previews/<name>.png
  --format F      with --weights: format of the --data clouds: auto (default), lc2wf, release,
                  line3dpp (Line3D++ .txt), limap (finaltracks/ folder) or obj (line OBJ); clouds
                  without ground truth (Line3D++, LIMAP, OBJ) need --gt
  --gt DIR        ground truth <name>.obj ('v' + 'f'/'l') or <name>.polyshape (Roof-Image mesh), or real
                  LoD2 city models (CityJSON, CityJSONSeq, CityGML; a folder or one file), buildings named
                  <file stem>__<building id> (dataset/README.md); a building the LoD2 clean-up rejects is
                  named on stderr and left out (exit 1)
  --lod L         city-model ground truth: the LoD 2.x to read (2.2, 2.1, or 2 = 2.0; default: each
                  building's highest)
  --data DIR      line-cloud files (one per building, file stem = name) holding the ground truth;
                  with --weights and --gt, only the clouds to run on
  --gt-seen-by N  with the ground truth of --data clouds: score against the GT edges at least N of the
                  cloud's cameras had in view (a street capture's seen part; 0 = the whole GT, default)
  --split FILE    building names, one per line (default: every ground-truth building in the folder)
  -o, --out OUT   writes metrics.md, metrics.json and per_building.csv there (created after the
                  arguments and inputs are checked)
  --units U       metres (default) or raw: units of the .obj files; raw coordinates are mapped to metres
                  with the ground truth's own transform (polyshape/line cloud) or divided by 20 (.obj)
  --gt-y-up       ground-truth .obj files are Y-up exports (Roof-Image res_obj, LC2WF house/)
  --strict-wed    also report the strict WED (charges spurious edges and extra vertices)
  --ties T        list (default: equal scores ranked in building order, then prediction order, as the
                  release) or group (precision/recall taken only after a whole group of equal scores)
  --method NAME   row label in the tables (default: name of the --pred folder)
  --precision P   with --weights: fp32 (default), bf16 or auto (see lc2wf-infer --help)
  -j, --threads N  with --weights: compute threads (default: all cores)
  -q, --quiet     no progress output

  --html          also write OUT/report.html: one self-contained page (opens offline) with the tables, a
                  per-building table sortable by every metric and a 3D viewer per building (needs Debian's
                  libjs-three; LC2WF_THREE_JS_DIR overrides /usr/share/javascript/three)
  --html-compare DIR  with --html: add the Table-2 rows of another lc2wf-eval --out folder (its metrics.json,
                  e.g. the --release-quirks run) to the report; may be repeated

The Markdown tables go to stdout. A building listed in the split without a prediction file (with
--weights: whose cloud could not be read) is scored as an empty wireframe, listed in the outputs and
named on stderr, also with -q, and the exit code is 1; with no prediction at all nothing is evaluated:
exit 3.
)";

struct Args {
  fs::path pred, gt, data, split, out, weights;
  bool previews = false;
  PostProcessFlags post;  // the post-processing flags of infer/post_process_flags.h
  std::string format = "auto";
  CoordinateUnits units = CoordinateUnits::kMetres;
  bool gt_y_up = false, strict_wed = false, quiet = false;
  std::string lod;  // --lod
  int gt_seen_by = 0;  // --gt-seen-by
  ApTieRule ties = ApTieRule::kListOrder;
  std::string method;
  int threads = 0;                     // -j, with --weights
  std::string precision = "fp32";      // --precision, with --weights
  bool html = false;                   // --html
  std::vector<fs::path> html_compare;  // --html-compare, repeatable
};

Args parse_args(int argc, char** argv) {
  Args a;
  auto value = [&](int& i) { return flag_value(argc, argv, i); };
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "--pred") a.pred = value(i);
    else if (f == "--weights") a.weights = value(i);
    else if (a.post.parse(f, argc, argv, i)) continue;
    else if (f == "--previews") a.previews = true;
    else if (f == "--format") a.format = value(i);
    else if (f == "--precision") a.precision = value(i);
    else if (f == "--gt") a.gt = value(i);
    else if (f == "--data") a.data = value(i);
    else if (f == "--split") a.split = value(i);
    else if (f == "-o" || f == "--out") a.out = value(i);
    else if (f == "-j" || f == "--threads") a.threads = threads_flag(f, value(i));
    else if (f == "--method") a.method = value(i);
    else if (f == "--gt-y-up") a.gt_y_up = true;
    else if (f == "--lod") a.lod = value(i);
    else if (f == "--gt-seen-by") a.gt_seen_by = static_cast<int>(std::min<long long>(parse_count_flag(f, value(i)), 1 << 20));  // more cameras than any cloud has: nothing seen
    else if (f == "--strict-wed") a.strict_wed = true;
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "--html") a.html = true;
    else if (f == "--html-compare") a.html_compare.push_back(value(i));
    else if (f == "--units") {
      const std::string u = value(i);
      if (u == "metres" || u == "meters") a.units = CoordinateUnits::kMetres;
      else if (u == "raw") a.units = CoordinateUnits::kRaw;
      else throw UsageError("--units must be 'metres' or 'raw', got '" + u + "'");
    } else if (f == "--ties") {
      const std::string t = value(i);
      if (t == "group") a.ties = ApTieRule::kGroupTies;
      else if (t == "list") a.ties = ApTieRule::kListOrder;
      else throw UsageError("--ties must be 'group' or 'list', got '" + t + "'");
    } else {
      throw UsageError("unknown argument '" + f + "'");
    }
  }
  if (a.pred.empty() == a.weights.empty()) throw UsageError("give exactly one of --pred DIR and --weights DIR");
#if !LC2WF_EVAL_WITH_WEIGHTS
  if (!a.weights.empty()) throw UsageError("--weights needs lc2wf built with the nn module");
#endif
  if (!a.weights.empty() && a.data.empty()) throw UsageError("--weights needs --data DIR (the line clouds to run on)");
  if (a.weights.empty() && (a.post.any() || a.previews || a.format != "auto" || a.precision != "fp32"))
    throw UsageError(
        "--release-quirks, --no-junction-refine, --min-confidence, --pair-support, --edge-support, --edge-support-everywhere, --judge-degree-above, --edge-cameras, --drop-flat-parts, --nms-radius, --max-offset, --sampling-passes, --density-seeds, --test-time-views, --edge-test-time-views, --max-segment-length, --max-pairs, --max-pairs-per-junction, --crossing-distance, --previews, --format and "
        "--precision only apply with --weights");
  a.post.options();  // checks the values before anything is written
#if LC2WF_EVAL_WITH_WEIGHTS
  try {
    parse_cloud_format(a.format, "--format");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  precision_flag(a.precision);
#endif
  // With --weights, --data holds the clouds and --gt (optional) the ground truth.
  if (a.weights.empty() && a.gt.empty() == a.data.empty()) throw UsageError("give exactly one of --gt DIR and --data DIR");
  if (a.gt.empty() && a.data.empty()) throw UsageError("give --gt DIR or --data DIR");
  if (!a.html_compare.empty() && !a.html) throw UsageError("--html-compare only applies with --html");
  if (a.gt_seen_by > 0 && !a.gt.empty()) throw UsageError("--gt-seen-by needs the ground truth of --data line clouds (they carry the cameras), not --gt");
  if (a.out.empty()) throw UsageError("-o OUT is required");
  for (const fs::path& d : a.html_compare) {
    const fs::path metrics = d / "metrics.json";
    // A FIFO or folder there is named for what it is (checked before opening: a FIFO blocks).
    if (const std::string problem = input_file_problem(metrics); !problem.empty())
      throw std::runtime_error("--html-compare: " + metrics.string() + ": " + problem);
    if (!fs::is_regular_file(metrics)) throw std::runtime_error("--html-compare: '" + metrics.string() + "' does not exist");
  }
  // Inputs that are not there are data errors (exit 3), found before anything is written.
  for (const fs::path& d : {a.weights.empty() ? a.pred : a.weights, a.gt.empty() ? a.data : a.gt, a.data.empty() ? a.gt : a.data})
    if (!fs::is_directory(d) && !(d == a.gt && is_city_model_file_name(d) && fs::is_regular_file(d)))  // --gt may be one city-model file
      throw std::runtime_error("'" + d.string() + "' is not a folder");
  if (!a.lod.empty() && normalise_lod2(a.lod).empty()) throw UsageError("--lod must be a LoD 2.x such as 2.2, 2.0 or 2, got '" + a.lod + "'");
  if (!a.split.empty() && !fs::is_regular_file(a.split))
    throw std::runtime_error("split file '" + a.split.string() + "' does not exist");
  if (!a.weights.empty()) a.pred = a.out / "predictions";
  if (a.method.empty() && !a.weights.empty())
    a.method = fs::absolute(a.weights).lexically_normal().filename().string() + (a.post.release_quirks ? " (release quirks)" : "");
  if (a.method.empty()) a.method = fs::absolute(a.pred).lexically_normal().filename().string();
  if (a.method.empty()) a.method = "prediction";
  return a;
}

// The first names of a list, quoted, for a message that must say which buildings it means.
std::string quoted_names(const std::vector<std::string>& names, size_t shown = 20) {
  std::string out;
  for (size_t k = 0; k < std::min(names.size(), shown); ++k) out += (k ? ", '" : "'") + names[k] + "'";
  return names.size() > shown ? out + ", ..." : out;
}

int run(const Args& a) {
  GroundTruthSource source;
  source.kind = a.gt.empty() ? GroundTruthSource::Kind::kLineCloudDir : GroundTruthSource::Kind::kMeshDir;
  source.dir = a.gt.empty() ? a.data : a.gt;
  source.obj_units = a.units;
  source.obj_y_up = a.gt_y_up;
  source.lod = a.lod;
  source.seen_by_cameras = a.gt_seen_by;

  const std::vector<std::string> names = a.split.empty() ? list_ground_truth_names(source) : read_name_list(a.split);
  if (names.empty())
    throw std::runtime_error("no buildings to evaluate (" + (a.split.empty() ? source.dir : a.split).string() + " lists none)");
  // Where the names came from, for the errors about them: a name from a split list is the list's problem.
  const std::string listed = a.split.empty() ? std::string() : " listed in " + a.split.string();
  if (a.weights.empty() && std::none_of(names.begin(), names.end(), [&](const std::string& n) { return fs::exists(a.pred / (n + ".obj")); }))
    throw std::runtime_error("nothing to evaluate: none of the " + std::to_string(names.size()) + " buildings" + listed + " (" +
                             quoted_names(names) + ") has a prediction in " + a.pred.string());

  // Scoring again the predictions an earlier --weights run left in OUT (e.g. to add --html) keeps its record
  // of how they were made and what they cost; a --weights run replaces it.
  std::optional<InferenceTiming> inference_summary = recorded_inference(a.out, a.pred, names.size());
#if LC2WF_EVAL_WITH_WEIGHTS
  if (!a.weights.empty()) {
    // Inference on every listed building, then the usual scoring of what it wrote.
    set_num_threads(a.threads);
    std::vector<fs::path> clouds;
    for (const std::string& name : names) clouds.push_back(find_cloud_file(a.data, name));
    const WireframePredictor predictor(a.weights);  // before OUT is created: missing weights write nothing
    BatchInferenceOptions inference;
    inference.post = a.post.options();
    inference.quiet = a.quiet;
    inference.precision = precision_flag(a.precision);
    inference.format = parse_cloud_format(a.format, "--format");
    if (a.previews) inference.preview_path = [&a](const std::string& name) { return a.out / "previews" / (name + ".png"); };
    const BatchInferenceSummary s = infer_clouds(predictor, clouds, a.pred, inference);
    inference_summary = s;
    if (s.failed > 0) {
      std::fprintf(stderr, "lc2wf-eval: %d line cloud(s) could not be read (named above): scored as empty wireframes\n", s.failed);
      if (s.buildings == 0) return kExitDataError;
      // A prediction left in OUT by an earlier run must not stand in for the one that failed now.
      for (const std::string& name : names)
        if (std::find(s.names.begin(), s.names.end(), name) == s.names.end())
          for (const char* ext : {".obj", ".json"}) fs::remove(a.pred / (name + ext));
    }
    std::fprintf(stderr, "lc2wf-eval: inference %.3f s per building on average (max %.3f s), %d empty wireframe(s)\n",
                 s.buildings ? s.total_seconds / s.buildings : 0.0, s.max_seconds, s.empty);
  }
#endif

  EvalOptions options;
  options.ties = a.ties;
  options.strict_wed = a.strict_wed;
  options.raw_per_metre = source.raw_per_metre;
  Evaluator evaluator(options);
  // Building3D-style counts in the frame of the line cloud (or of the GT corners when there is no cloud): with
  // --gt, the clouds of --data that inference ran on, so every kind of cloud of a building shares one frame.
  const bool clouds_beside_gt = !a.gt.empty() && !a.data.empty();
  const CloudFormat cloud_format = parse_cloud_format(a.format, "--format");
  std::vector<Building3dCounts> building3d;
  FaceReport faces;
  std::unique_ptr<HtmlReport> html;
  if (a.html) html = std::make_unique<HtmlReport>(HtmlReportOptions{default_three_js_dir()});
  std::unique_ptr<Progress> progress;
  if (!a.quiet) progress = std::make_unique<Progress>("evaluating", static_cast<int64_t>(names.size()));
  std::vector<std::string> evaluated, skipped_gt;  // ground truth loaded / rejected by the LoD2 clean-up
  for (const std::string& name : names) {
    const auto gt_path = find_ground_truth(source, name);
    if (!gt_path) {
      if (progress) progress->finish();
      // Names the files looked for: a reader of this message can then see which one is missing.
      const std::string looked_for = source.kind == GroundTruthSource::Kind::kMeshDir ? name + ".obj or " + name + ".polyshape"
                                                                                       : "line-cloud file " + name + ".*";
      throw std::runtime_error("no ground truth for building '" + name + "'" + listed + ": no " + looked_for + " in " +
                               source.dir.string());
    }
    GroundTruth gt;
    try {
      gt = load_ground_truth(source, *gt_path, name);
    } catch (const BuildingSkipped& e) {
      // A city-model building the LoD2 clean-up rejects: left out, named, exit 1.
      std::fprintf(stderr, "lc2wf-eval: skipped building without a usable ground truth: %s\n", e.what());
      skipped_gt.push_back(name);
      if (progress) progress->step();
      continue;
    }
    evaluated.push_back(name);
    const fs::path pred_path = a.pred / (name + ".obj");
    const bool missing = !fs::exists(pred_path);
    ScoredWireframe pred =
        missing ? ScoredWireframe{}
                : read_prediction(pred_path, a.units == CoordinateUnits::kRaw ? &gt.units : nullptr);
    std::vector<Segment3> cloud_segments = gt.cloud_segments;
    if (clouds_beside_gt && !missing) {  // (a cloud that could not be read has no prediction)
      // --weights predicted in the metric frame of the cloud, the GT is in its own: compare both in the GT's.
      LineCloud cloud = load_line_cloud(find_cloud_file(a.data, name), cloud_format);
      for (Vec3& p : pred.wireframe.junctions) p = cloud_to_ground_truth_frame(p, cloud.units, gt);
      for (Segment3& s : cloud.segments) s = {cloud_to_ground_truth_frame(s.a, cloud.units, gt), cloud_to_ground_truth_frame(s.b, cloud.units, gt)};
      cloud_segments = std::move(cloud.segments);
    }
    evaluator.add(name, pred, gt.wireframe, missing);
    SurfaceModel surfaces;  // LoD2 surfaces (infer/surfaces/), also drawn in the HTML report
    faces.buildings.push_back(evaluate_faces(name, pred.wireframe, pred.edge_scores, gt.mesh, &surfaces));
    faces.gt_has_faces = faces.gt_has_faces && !gt.mesh.faces.empty();
    const NormalisationFrame frame =
        cloud_segments.empty() ? frame_of_points(gt.wireframe.junctions) : frame_of_segments(cloud_segments);
    building3d.push_back(building3d_counts(pred, gt.wireframe, frame));
    if (html) html->add(pred, gt.wireframe, cloud_segments, options, &surfaces);
    if (progress) progress->step();
  }
  if (progress) progress->finish();

  const EvalReport report = evaluator.report();
  const Building3dReport b3d{summarize_building3d(building3d, {}, a.gt.empty() || clouds_beside_gt ? "line-cloud segment endpoints" : "GT corners"),
                             evaluated, building3d};
  write_eval_outputs(a.out, report, a.method, &b3d, inference_summary ? &*inference_summary : nullptr, &faces);
  const auto missing = report.missing_predictions();
  if (!missing.empty()) {
    // Exit 1 names what was skipped (metrics.json lists them all).
    std::fprintf(stderr, "lc2wf-eval: warning: %zu of %zu buildings%s have no prediction in %s (scored as empty): %s\n",
                 missing.size(), names.size(), listed.c_str(), a.pred.string().c_str(), quoted_names(missing, missing.size()).c_str());
  }
  std::fputs((eval_markdown(report, a.method) + building3d_markdown(b3d, a.method) + faces_markdown(faces, a.method)).c_str(), stdout);
  std::fprintf(stderr, "lc2wf-eval: wrote %s, %s and %s\n", (a.out / "metrics.md").string().c_str(),
               (a.out / "metrics.json").string().c_str(), (a.out / "per_building.csv").string().c_str());
  if (html)
    std::fprintf(stderr, "lc2wf-eval: report %s\n",
                 write_html_report(a.out, *html, report, a.method, &b3d, a.html_compare, a.weights, &faces).string().c_str());
  return missing.empty() && skipped_gt.empty() ? kExitDone : kExitPartly;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-eval", kUsage,
                          {kEnvOmpThreads, kEnvStorageCache, kEnvGemm,
                           {"LC2WF_THREE_JS_DIR", "--html: folder of three.js r111 (default /usr/share/javascript/three)"}}},
                         argc, argv, parse_args, run);
}
