// Per-stage cost of the raster dataset path on a synthetic L-shaped building (20 views, 640x480):
// render one view, LSD on one view, triangulation of 20 views, labelling, and the whole building.
#include <benchmark/benchmark.h>

#include "dataset/labels/labelling.h"
#include "dataset/synthetic/synthetic_building.h"
#include "tools/pipeline/cloud_builder.h"
#include "tools/render/camera_ring.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf {
namespace {

struct Fixture {
  Building building;
  std::vector<Camera> cameras;
  std::vector<RenderedView> views;
  std::vector<TriangulationView> segments;
  LineCloud cloud;

  Fixture() {
    LBuildingSpec spec;
    spec.end_x = RoofEnd::Gable;
    building = make_l_building("bench", spec);
    CameraRingOptions ring;
    cameras = make_camera_ring(building.mesh.vertices, ring);
    const RasterRenderer r(building.mesh, RasterOptions{});
    for (size_t v = 0; v < cameras.size(); ++v) views.push_back({r.render(cameras[v], v).image, cameras[v]});
    for (const auto& v : views) segments.push_back({v.camera, detect_segments(v.image, LsdOptions{})});
    cloud = build_line_cloud(building, views, CloudBuilderOptions{});
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void BM_RasterRenderView(benchmark::State& state) {
  const Fixture& f = fixture();
  RasterOptions o;
  o.supersample = static_cast<int>(state.range(0));
  const RasterRenderer r(f.building.mesh, o);
  for (auto _ : state) benchmark::DoNotOptimize(r.render(f.cameras[0], 0).image.data);
}
BENCHMARK(BM_RasterRenderView)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_LsdView(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(detect_segments(f.views[0].image, LsdOptions{}).size());
}
BENCHMARK(BM_LsdView)->Unit(benchmark::kMillisecond);

void BM_Triangulate20Views(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(triangulate_lines(f.segments, TriangulatorOptions{}).size());
  state.counters["lines"] = static_cast<double>(triangulate_lines(f.segments, TriangulatorOptions{}).size());
}
BENCHMARK(BM_Triangulate20Views)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LabelBySupport(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(label_by_support(f.cloud, f.building.mesh).size());
}
BENCHMARK(BM_LabelBySupport)->Unit(benchmark::kMillisecond);

// Everything for one building, as lc2wf-dataset --renderer raster does it (one thread per building).
void BM_RasterBuildingAllIn(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    const RasterRenderer r(f.building.mesh, RasterOptions{});
    std::vector<RenderedView> views;
    for (size_t v = 0; v < f.cameras.size(); ++v) views.push_back({r.render(f.cameras[v], v).image, f.cameras[v]});
    benchmark::DoNotOptimize(build_line_cloud(f.building, views, CloudBuilderOptions{}).segments.size());
  }
}
BENCHMARK(BM_RasterBuildingAllIn)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace lc2wf

BENCHMARK_MAIN();
