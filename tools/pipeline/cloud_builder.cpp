#include "tools/pipeline/cloud_builder.h"

#include <chrono>

#include "core/util/seconds_since.h"
#include "dataset/formats/errors.h"

namespace lc2wf {

void CloudBuilderOptions::Check() const {
  lsd.Check();
  triangulator.Check();
  labels.Check();
}

LineCloud build_line_cloud(const Building& building, const std::vector<RenderedView>& views, const CloudBuilderOptions& options,
                           CloudBuildStats* stats, const PolyMesh* occluders) {
  options.Check();
  CloudBuildStats local;
  CloudBuildStats& st = stats ? *stats : local;
  if (views.empty()) throw DataError(building.name, "no views (cameras missing)");

  auto t = std::chrono::steady_clock::now();
  std::vector<TriangulationView> tv(views.size());
  st.segments_per_view.assign(views.size(), 0);
  long long total_segments = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    tv[v].camera = views[v].camera;
    tv[v].segments = detect_segments(views[v].image, options.lsd);
    st.segments_per_view[v] = static_cast<int>(tv[v].segments.size());
    total_segments += st.segments_per_view[v];
  }
  st.seconds_lsd = seconds_since(t);
  if (total_segments == 0) throw DataError(building.name, "LSD found no 2D segment in any of " + std::to_string(views.size()) + " views");

  t = std::chrono::steady_clock::now();
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : building.mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const auto lines = triangulate_lines(tv, options.triangulator, Vec3(0.5 * (lo + hi)), &st.triangulation);
  st.seconds_triangulation = seconds_since(t);
  if (lines.empty()) throw DataError(building.name, "triangulation produced no 3D line");

  t = std::chrono::steady_clock::now();
  LineCloud cloud;
  cloud.name = building.name;
  cloud.units = building.units;
  cloud.wireframe = building.wireframe;
  for (const RenderedView& v : views) cloud.cameras.push_back(v.camera);
  for (const TriangulatedLine& l : lines) {
    cloud.segments.push_back(l.line);
    std::vector<Observation> obs;
    for (const SupportingSegment& s : l.support) obs.push_back({s.ref.view, tv[s.ref.view].segments[s.ref.segment]});
    cloud.support.push_back(std::move(obs));
  }
  cloud.labels = label_by_support(cloud, occluders ? *occluders : building.mesh, options.labels);
  st.seconds_labelling = seconds_since(t);
  return cloud;
}

}  // namespace lc2wf
