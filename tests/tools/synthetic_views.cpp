#include "tests/tools/synthetic_views.h"

#include <algorithm>
#include <random>

#include "dataset/labels/labelling.h"
#include "dataset/labels/visibility.h"

namespace lc2wf::test {

std::vector<TriangulationView> project_gt_segments(const Building& building, const std::vector<Camera>& cameras,
                                                   const Corruption& c, std::vector<std::vector<int>>* edge_of) {
  std::mt19937_64 gen(c.seed);
  auto uniform = [&gen]() { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
  auto normal = [&]() { return std::sqrt(-2.0 * std::log(uniform() + 1e-300)) * std::cos(6.283185307179586 * uniform()); };
  const MeshOccluder occ(building.mesh);
  const Wireframe& wf = building.wireframe;
  std::vector<TriangulationView> views(cameras.size());
  if (edge_of) edge_of->assign(cameras.size(), {});
  for (size_t v = 0; v < cameras.size(); ++v) {
    views[v].camera = cameras[v];
    for (size_t e = 0; e < wf.edges.size(); ++e) {
      const ProjectedEdge pe = project_edge(cameras[v], wf.junctions[wf.edges[e][0]], wf.junctions[wf.edges[e][1]], occ, 64, 0.02);
      for (const auto& iv : pe.visible) {
        Segment2 s{pe.p0 + iv[0] * (pe.p1 - pe.p0), pe.p0 + iv[1] * (pe.p1 - pe.p0)};
        if (s.length() < 4.0) continue;
        const Vec2 u = (s.b - s.a).normalized(), n(-u.y(), u.x());
        s.a += n * (c.perpendicular_sigma_px * normal()) + u * (c.along_jitter_px * (2 * uniform() - 1));
        s.b += n * (c.perpendicular_sigma_px * normal()) + u * (c.along_jitter_px * (2 * uniform() - 1));
        views[v].segments.push_back(s);
        if (edge_of) (*edge_of)[v].push_back(static_cast<int>(e));
      }
    }
    const int clutter = static_cast<int>(c.clutter_fraction * views[v].segments.size());
    for (int k = 0; k < clutter; ++k) {
      const Vec2 a(uniform() * cameras[v].width, uniform() * cameras[v].height);
      const double ang = uniform() * 3.141592653589793, len = 10 + 60 * uniform();
      views[v].segments.push_back({a, a + len * Vec2(std::cos(ang), std::sin(ang))});
      if (edge_of) (*edge_of)[v].push_back(-1);
    }
  }
  return views;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp(d.dot(p - a) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * d - p).norm();
}

}  // namespace lc2wf::test
