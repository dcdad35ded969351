#include "tools/triangulation/line_triangulator.h"

#include <chrono>
#include <set>
#include <stdexcept>
#include <string>

#include "tools/triangulation/view_geometry.h"

namespace lc2wf {

void TriangulatorOptions::Check() const {
  neighbours.Check();
  if (epipolar_overlap < 0 || epipolar_overlap >= 1) throw std::invalid_argument("TriangulatorOptions.epipolar_overlap must be in [0, 1)");
  if (min_ray_plane_angle_deg < 0 || min_ray_plane_angle_deg >= 90)
    throw std::invalid_argument("TriangulatorOptions.min_ray_plane_angle_deg must be in [0, 90)");
  if (min_view_angle_deg < 0 || min_view_angle_deg >= 90)
    throw std::invalid_argument("TriangulatorOptions.min_view_angle_deg must be in [0, 90)");
  if (endpoint_angle_deg < 0 || endpoint_angle_deg >= 90)
    throw std::invalid_argument("TriangulatorOptions.endpoint_angle_deg must be in [0, 90)");
  if (sigma_p_px < 0.1) throw std::invalid_argument("TriangulatorOptions.sigma_p_px must be >= 0.1");
  if (sigma_a_deg <= 0 || sigma_a_deg > 90) throw std::invalid_argument("TriangulatorOptions.sigma_a_deg must be in (0, 90]");
  if (min_similarity <= 0 || min_similarity >= 1) throw std::invalid_argument("TriangulatorOptions.min_similarity must be in (0, 1)");
  if (min_best_score < 0) throw std::invalid_argument("TriangulatorOptions.min_best_score must be >= 0");
  if (min_score_fraction < 0 || min_score_fraction > 1)
    throw std::invalid_argument("TriangulatorOptions.min_score_fraction must be in [0, 1]");
}

std::vector<TriangulatedLine> triangulate_lines(const std::vector<TriangulationView>& views, const TriangulatorOptions& options,
                                                const std::optional<Vec3>& scene_centre, TriangulationStats* stats) {
  options.Check();
  const int n = static_cast<int>(views.size());
  std::vector<Camera> cams;
  for (int v = 0; v < n; ++v) {
    const Camera& c = views[v].camera;
    if (!(c.K(0, 0) > 0 && c.K(1, 1) > 0) || !c.K.allFinite() || !c.R.allFinite() || !c.t.allFinite())
      throw std::invalid_argument("triangulate_lines: view " + std::to_string(v) + " has an invalid camera");
    cams.push_back(c);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const Vec3 centre = scene_centre ? *scene_centre : optical_axes_centre(cams);
  const auto nbrs = select_neighbours(cams, centre, options.neighbours);
  // Symmetric partner sets: each view is matched against its neighbours and every view that chose it.
  std::vector<std::set<int>> partners(n);
  for (int a = 0; a < n; ++a)
    for (int b : nbrs[a]) {
      partners[a].insert(b);
      partners[b].insert(a);
    }
  std::vector<ViewGeometry> geo(n);
  for (int v = 0; v < n; ++v) geo[v] = make_view_geometry(views[v], options.sigma_p_px);

  std::vector<std::vector<LineHypothesis>> hyps(n);
  std::vector<long long> tests(n, 0);
#pragma omp parallel for schedule(dynamic, 1)
  for (int a = 0; a < n; ++a) {
    for (int b : partners[a]) {
      auto m = match_view_pair(geo[a], geo[b], b, options, &tests[a]);
      hyps[a].insert(hyps[a].end(), m.begin(), m.end());
    }
  }
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<std::vector<TriangulatedLine>> per_view(n);
  std::vector<ScoreCounts> counts(n);
#pragma omp parallel for schedule(dynamic, 1)
  for (int a = 0; a < n; ++a)
    per_view[a] = score_view(a, static_cast<int>(views[a].segments.size()), hyps[a], geo[a], options, &counts[a]);
  const auto t2 = std::chrono::steady_clock::now();

  std::vector<TriangulatedLine> out;
  for (auto& v : per_view)
    for (auto& l : v) out.push_back(std::move(l));
  if (stats) {
    stats->views = n;
    stats->directed_pairs = 0;
    stats->candidate_tests = 0;
    stats->hypotheses = 0;
    stats->segments = stats->segments_with_hypothesis = stats->segments_with_two_views = 0;
    stats->segments_scored = stats->segments_kept = stats->kept_by_endpoints = 0;
    for (int a = 0; a < n; ++a) {
      stats->segments += static_cast<long long>(views[a].segments.size());
      stats->segments_with_hypothesis += counts[a].with_hypothesis;
      stats->segments_with_two_views += counts[a].with_two_views;
      stats->segments_scored += counts[a].scored;
      stats->segments_kept += counts[a].kept;
      stats->directed_pairs += static_cast<int>(partners[a].size());
      stats->candidate_tests += tests[a];
      stats->hypotheses += static_cast<long long>(hyps[a].size());
    }
    for (const auto& l : out) stats->kept_by_endpoints += l.by_endpoints;
    stats->seconds_matching = std::chrono::duration<double>(t1 - t0).count();
    stats->seconds_scoring = std::chrono::duration<double>(t2 - t1).count();
  }
  return out;
}

}  // namespace lc2wf
