// Cross-view scoring: a hypothesis for a source segment is confirmed by hypotheses for the same segment
// from other target views that agree in direction and in depth along the (shared) source rays.
#include <algorithm>
#include <cmath>

#include "tools/triangulation/view_geometry.h"

namespace lc2wf {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

struct Scorer {
  double inv_two_sigma_a_sq;  // 1 / (2 sigma_a^2), degrees
  double min_similarity;
  double source_k_sq;         // (sigma factor of the source view)^2

  // min(sim_a, sim_p1, sim_p2), or 0 unless above min_similarity. Cheap position tests first.
  double similarity(const LineHypothesis& h, const LineHypothesis& o) const {
    const double log_min = std::log(min_similarity);
    const double d1 = h.depth1 - o.depth1, d2 = h.depth2 - o.depth2;
    const double e1 = -d1 * d1 / (source_k_sq * h.depth1 * h.depth1 + h.target_var1);
    if (e1 <= log_min) return 0.0;
    const double e2 = -d2 * d2 / (source_k_sq * h.depth2 * h.depth2 + h.target_var2);
    if (e2 <= log_min) return 0.0;
    const double c = std::min(1.0, std::abs(h.direction.dot(o.direction)));
    const double alpha = std::acos(c) * kRadToDeg;
    const double ea = -alpha * alpha * inv_two_sigma_a_sq;
    if (ea <= log_min) return 0.0;
    return std::exp(std::min({e1, e2, ea}));
  }
};

}  // namespace

std::vector<TriangulatedLine> score_view(int view_index, int num_segments, const std::vector<LineHypothesis>& hypotheses,
                                         const ViewGeometry& view, const TriangulatorOptions& options, ScoreCounts* counts) {
  Scorer scorer{1.0 / (2.0 * options.sigma_a_deg * options.sigma_a_deg), options.min_similarity,
                view.sigma_factor * view.sigma_factor};
  // Group by source segment; inside a group keep (target view, input order) so ties break the same way.
  std::vector<std::vector<int>> by_segment(num_segments);
  for (size_t i = 0; i < hypotheses.size(); ++i) by_segment[hypotheses[i].source_segment].push_back(static_cast<int>(i));

  struct Best {
    int hyp = -1;
    double score = 0.0;
  };
  std::vector<Best> best(num_segments);
  double view_max = 0.0;
  for (int s = 0; s < num_segments; ++s) {
    const auto& group = by_segment[s];
    if (counts && !group.empty()) ++counts->with_hypothesis;
    if (group.size() < 2) continue;
    auto& idx = by_segment[s];
    std::stable_sort(idx.begin(), idx.end(), [&](int x, int y) { return hypotheses[x].target_view < hypotheses[y].target_view; });
    if (counts && hypotheses[idx.front()].target_view != hypotheses[idx.back()].target_view) ++counts->with_two_views;
    for (int hi : group) {
      const LineHypothesis& h = hypotheses[hi];
      double score = 0.0, run_best = 0.0;
      int run_view = -1;
      for (int oi : group) {
        const LineHypothesis& o = hypotheses[oi];
        if (o.target_view == h.target_view) continue;
        if (o.target_view != run_view) {
          score += run_best;
          run_best = 0.0;
          run_view = o.target_view;
        }
        run_best = std::max(run_best, scorer.similarity(h, o));
      }
      score += run_best;
      if (score > best[s].score) best[s] = {hi, score};
    }
    if (counts && best[s].score > 0) ++counts->scored;
    view_max = std::max(view_max, best[s].score);
  }

  const double threshold = std::max(options.min_best_score, options.min_score_fraction * view_max);
  std::vector<TriangulatedLine> lines;
  for (int s = 0; s < num_segments; ++s) {
    if (best[s].hyp < 0 || best[s].score <= threshold) continue;
    const LineHypothesis& h = hypotheses[best[s].hyp];
    TriangulatedLine line;
    line.line = {h.p1, h.p2};
    line.score = best[s].score;
    line.by_endpoints = h.by_endpoints;
    line.source = {view_index, s};
    line.support.push_back({{view_index, s}, 1.0});
    line.support.push_back({{h.target_view, h.target_segment}, 1.0});
    // One supporting target segment per other view: the best agreeing hypothesis of that view.
    int run_view = -1, run_seg = -1, run_hyp = -1;
    double run_best = 0.0;
    double weight = 1.0, depth1 = h.depth1, depth2 = h.depth2;
    auto flush = [&]() {
      if (run_view < 0 || run_best <= 0.0) return;
      line.support.push_back({{run_view, run_seg}, run_best});
      weight += run_best;
      depth1 += run_best * hypotheses[run_hyp].depth1;
      depth2 += run_best * hypotheses[run_hyp].depth2;
    };
    for (int oi : by_segment[s]) {
      const LineHypothesis& o = hypotheses[oi];
      if (o.target_view == h.target_view) continue;
      if (o.target_view != run_view) {
        flush();
        run_view = o.target_view;
        run_best = 0.0;
        run_seg = -1;
        run_hyp = -1;
      }
      const double sim = scorer.similarity(h, o);
      if (sim > run_best) {
        run_best = sim;
        run_seg = o.target_segment;
        run_hyp = oi;
      }
    }
    flush();
    if (options.average_depths) line.line = {view.centre + depth1 / weight * view.ray_a[s], view.centre + depth2 / weight * view.ray_b[s]};
    lines.push_back(std::move(line));
  }
  if (counts) counts->kept = static_cast<long long>(lines.size());
  return lines;
}

}  // namespace lc2wf
