#include "tools/pipeline/dataset_run.h"

#include "dataset/splits/splits.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "core/util/fnv1a.h"
#include "core/util/json_text.h"  // mesh names and error texts need not be UTF-8
#include "core/util/median.h"
#include "core/util/quantile.h"
#include "core/util/progress.h"
#include "core/util/version_json.h"
#include "core/util/workspace.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "dataset/formats/building_sources.h"
#include "dataset/formats/errors.h"
#include "dataset/labels/labelling.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/labels/visibility.h"

#include "core/util/seconds_since.h"

namespace lc2wf {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

using Clock = std::chrono::steady_clock;

// Upper bin edges of the length histogram, in units of the building's mean GT edge length.
const std::vector<double> kLengthBins = {0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0};

fs::path cloud_path(const fs::path& out, const std::string& name) { return out / "clouds" / (name + ".lcloud"); }

fs::path status_path(const fs::path& out, const std::string& name) { return out / "status" / (name + ".json"); }

// The view light the images get: the rasteriser's (RasterOptions::effective_view_light); Blender's is its own.
double effective_view_light(const DatasetRunOptions& o) {
  return o.renderer == RendererKind::Raster ? o.raster.effective_view_light() : 0.0;
}

// Done with the capture, pixel rule and view light asked for (statuses without them are orbits at a fixed
// image size under a constant ambient): a building done another way is redone.
bool is_done(const fs::path& out, const std::string& name, const DatasetRunOptions& o) {
  const fs::path sp = status_path(out, name);
  if (!fs::exists(sp) || !fs::exists(cloud_path(out, name))) return false;
  try {
    const Json st = Json::parse(read_file(sp));
    return st.value("ok", false) && st.value("capture", "orbit") == o.capture &&
           st.value("max_metres_per_pixel", 0.0) == o.max_metres_per_pixel &&
           st.value("view_light", 0.0) == effective_view_light(o);
  } catch (const std::exception&) {
    return false;  // unreadable status: redo the building
  }
}

// Renders, cameras and per-view projected GT (junctions; edges as [i, j, visible, visible_fraction]),
// the same files the Blender script writes.
void write_views(const fs::path& dir, const Building& b, const std::vector<RenderedView>& views) {
  fs::create_directories(dir);
  const MeshOccluder occ(b.mesh);
  Json cams = Json::array(), per_view = Json::array();
  for (size_t v = 0; v < views.size(); ++v) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu.png", v);
    std::vector<uchar> png;
    cv::imencode(".png", views[v].image, png);
    write_file_atomic(dir / name, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    const Camera& cam = views[v].camera;
    cams.push_back(camera_to_json(cam));
    Json junc = Json::array(), edges = Json::array();
    for (const Vec3& j : b.wireframe.junctions) {
      const Vec2 p = cam.project(j);
      junc.push_back({p.x(), p.y()});
    }
    for (const auto& e : b.wireframe.edges) {
      const ProjectedEdge pe = project_edge(cam, b.wireframe.junctions[e[0]], b.wireframe.junctions[e[1]], occ, 16, 0.02);
      double frac = 0;
      for (const auto& iv : pe.visible) frac += iv[1] - iv[0];
      edges.push_back({e[0], e[1], frac >= 0.5 ? 1 : 0, frac});
    }
    per_view.push_back({{"junc2D", junc}, {"edges", edges}});
  }
  write_file_atomic(dir / "cameras.json", cams.dump());
  write_file_atomic(dir / "views.json", per_view.dump());
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Counts and shape statistics of a finished cloud, for the status record.
void describe_cloud(const LineCloud& cloud, Json& st) {
  const Wireframe& wf = cloud.wireframe;
  double mean_edge = 0;
  for (const auto& e : wf.edges) mean_edge += (wf.junctions[e[0]] - wf.junctions[e[1]]).norm();
  mean_edge /= std::max<size_t>(1, wf.edges.size());
  int positives = 0, shorter = 0;
  std::vector<int> hist(kLengthBins.size() + 1, 0);
  std::vector<char> covered(wf.edges.size(), 0);
  // Accuracy of the positives: farther endpoint's distance to the labelled GT edge (segment), metres.
  Json positive_distance = Json::array();
  for (size_t i = 0; i < cloud.segments.size(); ++i) {
    const double r = cloud.segments[i].length() / std::max(mean_edge, 1e-12);
    shorter += r < 1.0;
    ++hist[std::upper_bound(kLengthBins.begin(), kLengthBins.end(), r) - kLengthBins.begin()];
    const SegmentLabel& l = cloud.labels[i];
    if (!l.f) continue;
    ++positives;
    const Vec3 &a = wf.junctions[l.i1], &b = wf.junctions[l.i2];
    const Segment3& seg = cloud.segments[i];
    const double d = std::max(point_segment_distance(seg.a, a, b), point_segment_distance(seg.b, a, b));
    positive_distance.push_back(std::round(d * 1e4) / 1e4);
    for (size_t e = 0; e < wf.edges.size(); ++e)
      if ((wf.edges[e][0] == l.i1 && wf.edges[e][1] == l.i2) || (wf.edges[e][0] == l.i2 && wf.edges[e][1] == l.i1)) covered[e] = 1;
  }
  st["segments"] = cloud.segments.size();
  st["positives"] = positives;
  st["shorter_than_mean_gt_edge"] = shorter;
  st["mean_gt_edge_m"] = mean_edge;
  st["gt_edges"] = wf.edges.size();
  st["gt_edges_covered"] = std::count(covered.begin(), covered.end(), 1);
  st["length_histogram"] = hist;
  st["positive_edge_distance_m"] = positive_distance;
}

// Where the 2D segments drop out on their way to 3D lines.
Json describe_triangulation(const TriangulationStats& t) {
  return {{"segments", t.segments},
          {"with_hypothesis", t.segments_with_hypothesis},
          {"with_two_target_views", t.segments_with_two_views},
          {"scored", t.segments_scored},
          {"kept", t.segments_kept},
          {"hypotheses", t.hypotheses}};
}

struct Job {
  std::string name;
  Building building;
  std::vector<Camera> cameras;
  std::vector<RenderedView> views;
  fs::path render_dir;  // Blender's output folder of this building
  PhotoScene scene;      // textures "photo": the clutter around the building
  PolyMesh scene_mesh;   // the building and that clutter (empty otherwise)
  double view_scale = 1.0;  // its images' size over the cameras' option (DatasetRunOptions::max_metres_per_pixel)
  Json status;
  bool failed = false;
};

void fail(Job& job, const std::string& reason) {
  job.failed = true;
  job.status["ok"] = false;
  job.status["error"] = reason;
}

void load_job(Job& job, const DatasetRunOptions& o, const BuildingCatalog& sources) {
  const auto t = Clock::now();
  try {
    try {
      job.building = sources.load(job.name, o.building);
    } catch (const Lod2Skipped& e) {
      job.status["skip_reason"] = e.reason();  // counted per reason in the summary
      throw;
    }
    job.view_scale = view_scale_for(job.building.mesh.vertices, o.cameras, o.max_metres_per_pixel, o.max_image_side);
    CameraRingOptions ring = capture_ring(scaled_ring(o.cameras, job.view_scale), o.capture);
    ring.seed = building_seed(job.name, o.seed);
    job.status["image_size"] = {ring.width, ring.height};
    job.cameras = make_camera_ring(job.building.mesh.vertices, ring);
    const std::string& textures = o.renderer == RendererKind::Raster ? o.raster.textures : o.blender.textures;
    if (textures == "photo") {
      std::vector<Vec3> centres;
      for (const Camera& c : job.cameras) centres.push_back(c.center());
      job.scene = make_photo_scene(job.building.mesh, centres, o.photo, building_seed(job.name, o.seed));
      job.scene_mesh = scene_mesh(job.building.mesh, job.scene);
      job.status["clutter_faces"] = job.scene.clutter.faces.size();
    }
  } catch (const std::exception& e) {
    fail(job, std::string("load: ") + e.what());
  }
  job.status["seconds"]["load"] = seconds_since(t);
}

void render_raster(Job& job, const DatasetRunOptions& o) {
  const auto t = Clock::now();
  try {
    RasterOptions ro = o.raster;
    ro.seed = building_seed(job.name, o.seed);
    const RasterRenderer renderer(job.building.mesh, ro, job.scene);
    for (size_t v = 0; v < job.cameras.size(); ++v) job.views.push_back({renderer.render(job.cameras[v], v).image, job.cameras[v]});
  } catch (const std::exception& e) {
    fail(job, std::string("render: ") + e.what());
  }
  job.status["seconds"]["render"] = seconds_since(t);
}

void finish_job(Job& job, const DatasetRunOptions& o) {
  if (!job.failed) {
    try {
      if (o.keep_views && o.renderer == RendererKind::Raster) write_views(o.out / "views" / job.name, job.building, job.views);
      CloudBuildStats cs;
      CloudBuilderOptions cloud_options = o.cloud;
      cloud_options.lsd = scaled_lsd(o.cloud.lsd, job.view_scale);
      const LineCloud cloud = build_line_cloud(job.building, job.views, cloud_options, &cs, job.scene_mesh.faces.empty() ? nullptr : &job.scene_mesh);
      const auto t = Clock::now();
      write_line_cloud(cloud_path(o.out, job.name), cloud);
      job.status["seconds"]["write"] = seconds_since(t);
      job.status["seconds"]["lsd"] = cs.seconds_lsd;
      job.status["seconds"]["triangulation"] = cs.seconds_triangulation;
      job.status["seconds"]["labelling"] = cs.seconds_labelling;
      long long segs2d = 0;
      for (int n : cs.segments_per_view) segs2d += n;
      job.status["views"] = job.views.size();
      job.status["segments_2d"] = segs2d;
      describe_cloud(cloud, job.status);
      job.status["triangulation"] = describe_triangulation(cs.triangulation);
      job.status["ok"] = true;
    } catch (const std::exception& e) {
      fail(job, e.what());
    }
  }
  if (!job.render_dir.empty() && !o.keep_views) fs::remove_all(job.render_dir);
  job.views.clear();
  try {
    write_file_atomic(status_path(o.out, job.name), json_text(job.status, 1));
  } catch (const std::exception& e) {
    // An exception leaving an OpenMP worker aborts the process: count the building as failed (redone next run).
    job.failed = true;
    std::fprintf(stderr, "lc2wf-dataset: %s: cannot write its status: %s\n", job.name.c_str(), e.what());
  }
}

}  // namespace

void DatasetRunOptions::Check() const {
  if (meshes.empty()) throw std::invalid_argument("DatasetRunOptions.meshes is empty");
  if (out.empty()) throw std::invalid_argument("DatasetRunOptions.out is empty");
  cameras.Check();
  if (!is_capture_kind(capture))
    throw std::invalid_argument("DatasetRunOptions.capture must be " + std::string(kCaptureKinds) + ", got '" + capture + "'");
  capture_ring(cameras, capture).Check();
  raster.Check();
  if (renderer == RendererKind::Blender) blender.Check();
  photo.Check();
  cloud.Check();
  building.Check();
  sources.Check();
  if (blender_batch < 1) throw std::invalid_argument("DatasetRunOptions.blender_batch must be >= 1");
  if (threads < 0) throw std::invalid_argument("DatasetRunOptions.threads must be >= 0");
  if (shard_count < 1 || shard_index < 0 || shard_index >= shard_count)
    throw std::invalid_argument("DatasetRunOptions.shard_index/shard_count must satisfy 0 <= index < count");
  if (limit < 0) throw std::invalid_argument("DatasetRunOptions.limit must be >= 0");
  if (!(std::isfinite(max_metres_per_pixel) && max_metres_per_pixel >= 0))
    throw std::invalid_argument("DatasetRunOptions.max_metres_per_pixel must be >= 0 (0 = off)");
  if (max_image_side < std::max(cameras.width, cameras.height) || max_image_side > 16384)
    throw std::invalid_argument("DatasetRunOptions.max_image_side must be in [the cameras' larger side, 16384]");
}

uint64_t building_seed(const std::string& name, uint64_t seed) {
  return fnv1a64(name) ^ (seed * 0x9E3779B97F4A7C15ull);
}

std::vector<std::string> shard_names(const std::vector<std::string>& sorted, int shard_index, int shard_count, int limit) {
  std::vector<std::string> out;
  for (size_t k = 0; k < sorted.size(); ++k)
    if (static_cast<int>(k % shard_count) == shard_index) out.push_back(sorted[k]);
  if (limit > 0 && static_cast<int>(out.size()) > limit) out.resize(limit);
  return out;
}

Json summarise(const std::vector<Json>& statuses) {
  Json s;
  int done = 0;
  Json failed = Json::array();
  std::vector<double> segs, segs2d, pos_share, shorter_share, coverage;
  std::vector<long long> hist(kLengthBins.size() + 1, 0);
  long long total_segments = 0, total_pos = 0, total_shorter = 0;
  std::map<std::string, double> seconds;
  std::map<std::string, double> dropout;
  std::vector<double> positive_distance;
  int with_dropout = 0;
  for (const Json& st : statuses) {
    if (!st.value("ok", false)) {
      failed.push_back({{"name", st.value("name", "")}, {"error", st.value("error", "unknown")}});
      continue;
    }
    ++done;
    const double n = st["segments"].get<double>();
    segs.push_back(n);
    segs2d.push_back(st["segments_2d"].get<double>());
    pos_share.push_back(st["positives"].get<double>() / std::max(1.0, n));
    shorter_share.push_back(st["shorter_than_mean_gt_edge"].get<double>() / std::max(1.0, n));
    coverage.push_back(st["gt_edges_covered"].get<double>() / std::max(1.0, st["gt_edges"].get<double>()));
    total_segments += st["segments"].get<long long>();
    total_pos += st["positives"].get<long long>();
    total_shorter += st["shorter_than_mean_gt_edge"].get<long long>();
    const auto h = st["length_histogram"].get<std::vector<long long>>();
    for (size_t i = 0; i < hist.size() && i < h.size(); ++i) hist[i] += h[i];
    for (auto& [k, v] : st["seconds"].items()) seconds[k] += v.get<double>();
    if (st.contains("triangulation")) {
      ++with_dropout;
      for (auto& [k, v] : st["triangulation"].items()) dropout[k] += v.get<double>();
    }
    if (st.contains("positive_edge_distance_m"))
      for (const auto& d : st["positive_edge_distance_m"]) positive_distance.push_back(d.get<double>());
  }
  auto mean = [](const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m += x;
    return v.empty() ? 0.0 : m / v.size();
  };
  s["buildings"] = statuses.size();
  s["done"] = done;
  s["failed"] = failed;
  s["segments_per_building"] = {{"mean", mean(segs)}, {"median", median(segs)}};
  s["segments_2d_per_building"] = {{"mean", mean(segs2d)}, {"median", median(segs2d)}};
  s["positive_share"] = {{"pooled", total_segments ? static_cast<double>(total_pos) / total_segments : 0.0}, {"mean", mean(pos_share)}};
  s["shorter_than_mean_gt_edge_share"] = {{"pooled", total_segments ? static_cast<double>(total_shorter) / total_segments : 0.0},
                                          {"mean", mean(shorter_share)}};
  s["gt_edge_coverage_by_positives"] = {{"mean", mean(coverage)}, {"median", median(coverage)}};
  Json h = Json::array();
  for (size_t i = 0; i < hist.size(); ++i) {
    const std::string hi = i < kLengthBins.size() ? std::to_string(kLengthBins[i]).substr(0, 4) : "inf";
    h.push_back({{"below_x_mean_gt_edge", hi}, {"share", total_segments ? static_cast<double>(hist[i]) / total_segments : 0.0}});
  }
  s["length_histogram"] = h;
  Json sec;
  for (const auto& [k, v] : seconds) sec[k] = done ? v / done : 0.0;
  s["seconds_per_building"] = sec;
  Json drop;
  for (const auto& [k, v] : dropout) drop[k] = v / std::max(1, with_dropout);
  s["triangulation_per_building"] = drop;
  s["positive_edge_distance_m"] = {{"median", quantile(positive_distance, 0.5)}, {"p90", quantile(positive_distance, 0.9)}};
  return s;
}

Json run_dataset(const DatasetRunOptions& o) {
  o.Check();
  if (!fs::exists(o.meshes)) throw DataError(o.meshes.string(), "mesh folder or file does not exist");
  const BuildingCatalog sources(o.meshes, o.sources);
  std::vector<std::string> all = sources.names();
  if (!o.names.empty()) {  // a split of a folder that holds more buildings: every listed one must be there
    std::vector<std::string> wanted = read_name_list(o.names);
    std::sort(wanted.begin(), wanted.end());
    for (const std::string& n : wanted)
      if (!std::binary_search(all.begin(), all.end(), n))
        throw DataError(o.names.string(), "building '" + n + "' is not in " + o.meshes.string());
    all = std::move(wanted);
  }
  if (all.empty()) throw DataError(o.meshes.string(), "no building (.polyshape, CityJSON, CityJSONSeq or CityGML with the LoD asked for): nothing to do");
  const auto names = shard_names(all, o.shard_index, o.shard_count, o.limit);
  if (names.empty())
    throw DataError(o.meshes.string(), "shard " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) + " of its " +
                                           std::to_string(all.size()) + " buildings is empty: nothing to do");
  fs::create_directories(o.out / "clouds");
  fs::create_directories(o.out / "status");
  if (o.threads > 0) omp_set_num_threads(o.threads);

  std::vector<std::string> todo;
  for (const auto& n : names)
    if (!is_done(o.out, n, o)) todo.push_back(n);
  const auto start = Clock::now();
  {
    std::mutex mu;
    std::unique_ptr<Progress> bar;
    if (o.progress) bar = std::make_unique<Progress>("lc2wf-dataset", static_cast<int64_t>(todo.size()));
    int failed = 0;
    auto report = [&](const Job& job) {
      std::lock_guard<std::mutex> lock(mu);
      failed += job.failed;
      if (bar) bar->step(1, failed ? std::to_string(failed) + " failed" : "");
    };
    auto make_job = [&o](const std::string& name) {
      Job job;
      job.name = name;
      job.status["name"] = name;
      job.status["capture"] = o.capture;
      job.status["max_metres_per_pixel"] = o.max_metres_per_pixel;
      job.status["view_light"] = effective_view_light(o);
      job.status["seconds"] = Json::object();
      return job;
    };
    if (o.renderer == RendererKind::Raster) {
#pragma omp parallel for schedule(dynamic, 1)
      for (size_t i = 0; i < todo.size(); ++i) {
        Job job = make_job(todo[i]);
        load_job(job, o, sources);
        if (!job.failed) render_raster(job, o);
        finish_job(job, o);
        report(job);
      }
    } else {
      // Blender's job file and log, and the renders unless kept: a private scratch folder, never inside OUT.
      Workspace scratch({}, false);
      for (size_t first = 0; first < todo.size(); first += o.blender_batch) {
        const size_t last = std::min(todo.size(), first + o.blender_batch);
        std::vector<Job> jobs;
        for (size_t i = first; i < last; ++i) jobs.push_back(make_job(todo[i]));
#pragma omp parallel for schedule(dynamic, 1)
        for (size_t i = 0; i < jobs.size(); ++i) load_job(jobs[i], o, sources);
        std::vector<BlenderBuilding> batch;
        std::vector<size_t> index;
        for (size_t i = 0; i < jobs.size(); ++i) {
          if (jobs[i].failed) continue;
          jobs[i].render_dir = o.keep_views ? o.out / "views" / jobs[i].name : scratch.root() / "renders" / jobs[i].name;
          batch.push_back({&jobs[i].building, jobs[i].cameras, jobs[i].render_dir, building_seed(jobs[i].name, o.seed), &jobs[i].scene});
          index.push_back(i);
        }
        const auto t = Clock::now();
        BlenderOptions bo = o.blender;
        if (bo.threads == 0 && o.threads > 0) bo.threads = o.threads;
        bo.gt_views = o.keep_views;  // the GT projection is only read by people looking at kept views
        const auto results = render_with_blender(batch, bo, scratch.root());
        const double per_building = seconds_since(t) / std::max<size_t>(1, batch.size());
        for (size_t k = 0; k < index.size(); ++k) {
          Job& job = jobs[index[k]];
          job.status["seconds"]["render"] = per_building;
          if (!results[k].error.empty())
            fail(job, "render: " + results[k].error);
          else
            job.views = results[k].views;
        }
#pragma omp parallel for schedule(dynamic, 1)
        for (size_t i = 0; i < jobs.size(); ++i) {
          finish_job(jobs[i], o);
          report(jobs[i]);
        }
      }
      // job.json and blender.log: kept when something failed, for the error messages that name the log.
      if (failed > 0) scratch.keep();
    }
  }
  std::vector<Json> statuses;
  for (const auto& n : names) {
    const fs::path sp = status_path(o.out, n);
    if (!fs::exists(sp)) continue;
    try {
      statuses.push_back(Json::parse(read_file(sp)));
    } catch (const std::exception& e) {
      statuses.push_back({{"name", n}, {"ok", false}, {"error", std::string("unreadable status: ") + e.what()}});
    }
  }
  Json summary = summarise(statuses);
  // City models: buildings the LoD2 clean-up rejected, per reason; files that could not be read are failures.
  std::map<std::string, int> skipped_by_reason;
  for (const Json& st : statuses)
    if (st.contains("skip_reason")) ++skipped_by_reason[st["skip_reason"].get<std::string>()];
  summary["skipped_by_reason"] = skipped_by_reason;
  for (const SourceFileListing& f : sources.files())
    if (!f.error.empty()) summary["failed"].push_back({{"name", f.file.string()}, {"error", "unreadable source file: " + f.error}});
  summary["shard"] = std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count);
  summary["renderer"] = o.renderer == RendererKind::Raster ? "raster" : "blender";
  summary["textures"] = o.renderer == RendererKind::Raster ? o.raster.textures : o.blender.textures;
  summary["capture"] = o.capture;
  summary["max_metres_per_pixel"] = o.max_metres_per_pixel;
  summary["view_light"] = effective_view_light(o);
  summary["command"] = o.command_line;
  add_version_fields(summary);
  summary["processed_this_run"] = todo.size();
  summary["skipped_already_done"] = names.size() - todo.size();
  summary["wall_seconds_this_run"] = seconds_since(start);
  const std::string file = o.shard_count == 1 ? "summary.json"
                                              : "summary-shard-" + std::to_string(o.shard_index) + "-of-" + std::to_string(o.shard_count) + ".json";
  write_file_atomic(o.out / file, json_text(summary, 2));
  return summary;
}

}  // namespace lc2wf
