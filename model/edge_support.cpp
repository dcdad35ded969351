#include "model/edge_support.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/geometry/wireframe_graph.h"
#include "model/edge_visibility.h"

namespace lc2wf {

void EdgeSupportOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("EdgeSupportOptions." + what); };
  if (!(min_support >= 0 && min_support <= 1)) fail("min_support must be in [0, 1]");
  if (!(radius_m > 0) || !std::isfinite(radius_m)) fail("radius_m must be a positive distance in metres");
  if (!(max_angle_deg > 0 && max_angle_deg <= 90)) fail("max_angle_deg must be in (0, 90]");
  if (min_cameras < 0) fail("min_cameras must be >= 0");
  if (judge_degree_above < 0) fail("judge_degree_above must be >= 0 (0: off)");
  if (!(judge_min_support >= 0 && judge_min_support <= 1)) fail("judge_min_support must be in [0, 1]");
  if (!(occlusion_tolerance_m >= 0) || !std::isfinite(occlusion_tolerance_m))
    fail("occlusion_tolerance_m must be a distance >= 0 in metres");
}

SupportedEdges keep_supported_edges(const ScoredWireframe& in, const std::vector<Segment3>& segments,
                                    const std::vector<Camera>& cameras, const EdgeSupportOptions& options,
                                    JudgedEdges judged) {
  options.Check();
  in.check("keep_supported_edges");
  SupportedEdges out;
  const bool every = judged == JudgedEdges::every_edge;
  if (!options.enabled() || (!every && options.judge_degree_above == 0)) {
    out.wireframe = in;
    return out;
  }
  const std::vector<int> degree = junction_degrees(in.wireframe);
  const SegmentSupport support(segments);
  const bool ask_cameras = every && options.min_cameras > 0 && !cameras.empty();
  const FootprintOccluder occluder(ask_cameras ? in.wireframe : Wireframe{});
  ScoredWireframe kept;
  kept.wireframe.junctions = in.wireframe.junctions;
  kept.junction_scores = in.junction_scores;
  for (size_t e = 0; e < in.wireframe.edges.size(); ++e) {
    const auto [a, b] = in.wireframe.edges[e];
    const Vec3& u = in.wireframe.junctions[a];
    const Vec3& v = in.wireframe.junctions[b];
    const bool exempt = !every && std::max(degree[a], degree[b]) <= options.judge_degree_above;
    const double share = every ? options.min_support : options.judge_min_support;
    const bool lines = exempt || support.support(u, v, options.radius_m, options.max_angle_deg) >= share;
    const bool seen = !lines && ask_cameras &&
                      cameras_seeing(u, v, cameras, occluder, options.occlusion_tolerance_m) >= options.min_cameras;
    if (lines || seen) {
      kept.wireframe.edges.push_back(in.wireframe.edges[e]);
      kept.edge_scores.push_back(in.edge_scores[e]);
      out.kept_by_cameras += seen;
    } else {
      ++out.dropped_edges;
    }
  }
  out.wireframe = referenced_junctions_only(kept);
  // Junctions the input had no edge for are not counted: only those this rule left alone.
  const ScoredWireframe before = referenced_junctions_only(in);
  out.dropped_junctions = static_cast<int>(before.wireframe.junctions.size() - out.wireframe.wireframe.junctions.size());
  return out;
}

}  // namespace lc2wf
