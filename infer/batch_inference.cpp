#include "infer/batch_inference.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>

#include "core/parallel.h"
#include "core/storage_cache.h"
#include "core/util/cli.h"
#include "core/util/atomic_file.h"
#include "core/util/progress.h"
#include "dataset/photo/camera_coverage.h"
#include "infer/prediction_io.h"
#include "infer/preview.h"
#include "infer/surfaces/surface_writers.h"
#include "infer/surfaces/wireframe_surfaces.h"

namespace lc2wf {

MatmulPrecision precision_flag(const std::string& value) {
  try {
    return parse_matmul_precision(value, "--precision");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

BatchInferenceSummary infer_clouds(const WireframePredictor& predictor, const std::vector<std::filesystem::path>& clouds,
                                   const std::filesystem::path& out_dir, const BatchInferenceOptions& o) {
  o.post.Check();
  const MatmulPrecisionGuard precision(o.precision);
  const StorageCacheSlackGuard slack(kBatchInferenceSlack);
  const StorageCacheHugePagesGuard small_pages(false);  // a one-off fault must not stall (storage_cache.h)
  BatchInferenceSummary s;
  s.threads = num_threads();
  s.precision = to_string(o.precision);
  s.record_selection(o.post);
  std::unique_ptr<Progress> bar;
  if (!o.quiet) bar = std::make_unique<Progress>("inferring", static_cast<int64_t>(clouds.size()));
  for (const auto& path : clouds) {
    // Outputs are named after the file stem, never the name stored inside the file ("../x", "/etc/y", ".").
    const std::string name = path.stem().string();
    if (!is_plain_file_name(name)) {
      std::fprintf(stderr, "%slc2wf: skipping %s: its stem '%s' cannot name an output file\n", bar ? "\n" : "", path.string().c_str(),
                   name.c_str());
      ++s.failed;
      if (bar) bar->step();
      continue;
    }
    LineCloud cloud;
    InferenceResult r;
    try {
      cloud = load_line_cloud(path, o.format, o.raw_per_metre);
      if (o.map_frame.applies_to(cloud)) {
        const auto t0 = std::chrono::steady_clock::now();
        FramedInference f = infer_in_metric_frame(predictor, cloud, o.post, o.map_frame);
        s.frame_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++s.framed;
        std::filesystem::create_directories(out_dir);
        write_file_atomic(out_dir / (name + ".frame.json"), f.report.dump(2));
        if (!o.quiet) std::fprintf(stderr, "%s%s: %s\n", bar ? "\n" : "", name.c_str(), f.summary.c_str());
        if (!f.warning.empty()) std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), f.warning.c_str());  // also with --quiet
        cloud = std::move(f.cloud);
        r = std::move(f.inference);
      } else {
        r = predictor.predict(cloud, o.post);
      }
    } catch (const std::exception& e) {  // one bad cloud must not end the batch
      std::fprintf(stderr, "%slc2wf: skipping %s: %s\n", bar ? "\n" : "", path.string().c_str(), e.what());
      ++s.failed;
      if (bar) bar->step();
      continue;
    }
    const double seconds = r.junction_seconds + r.edge_seconds + r.post_seconds;
    s.total_seconds += seconds;
    s.max_seconds = std::max(s.max_seconds, seconds);
    s.junction_seconds += r.junction_seconds;
    s.edge_seconds += r.edge_seconds;
    s.post_seconds += r.post_seconds;
    s.pairs += static_cast<int64_t>(r.pairs.size());
    ++s.buildings;
    if (r.wireframe.wireframe.edges.empty()) ++s.empty;
    if (r.segments_cut) ++s.cut;
    s.names.push_back(name);
    // A cloud with cameras says which sides they saw, as lc2wf-reconstruct's report does.
    if (!cloud.cameras.empty())
      r.notes.push_back("coverage: " + camera_coverage(cloud.cameras, r.wireframe.wireframe, cloud.segments).summary());
    write_prediction(out_dir, name, r.wireframe, r.notes, o.raw_units ? &cloud.units : nullptr);
    if (o.write_surfaces) {
      const auto t0 = std::chrono::steady_clock::now();
      const SurfaceModel surfaces = surfaces_from_wireframe(r.wireframe.wireframe, r.wireframe.edge_scores, o.surfaces);
      s.surface_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      s.closed_solids += surfaces.closed_solid() ? 1 : 0;
      SurfaceOutputOptions so;
      so.raw_units = o.raw_units;
      so.source_units = cloud.units;
      write_surface_outputs(out_dir, name, surfaces, so);
    }
    if (o.preview_path)
      write_preview(o.preview_path(name), cloud, r.wireframe.wireframe,
                    cloud.wireframe.junctions.empty() ? nullptr : &cloud.wireframe);
    if (!o.quiet && r.wireframe.wireframe.edges.empty()) {  // notes are in the JSON either way
      std::string text;
      for (const auto& n : r.notes) text += (text.empty() ? "" : "; ") + n;
      std::fprintf(stderr, "%s%s: %s\n", bar ? "\n" : "", name.c_str(), text.c_str());
    }
    if (bar) bar->step(1, name);
  }
  return s;
}

}  // namespace lc2wf
