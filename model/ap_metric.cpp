#include "model/ap_metric.h"

#include <algorithm>
#include <limits>

namespace lc2wf {

std::vector<RankedHit> greedy_nearest_match(const std::vector<double>& scores, int num_gt, double threshold,
                                            double min_score, const std::function<double(int, int)>& distance) {
  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(scores.size()); ++i)
    if (scores[i] > min_score) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });

  std::vector<char> hit(num_gt, 0);
  std::vector<RankedHit> out;
  out.reserve(order.size());
  for (int i : order) {
    int nearest = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int j = 0; j < num_gt; ++j) {
      const double d = distance(i, j);
      if (d < best) best = d, nearest = j;
    }
    // No fallback to the second-nearest GT element: that is the release's rule.
    const bool tp = nearest >= 0 && best < threshold && !hit[nearest];
    if (tp) hit[nearest] = 1;
    out.push_back({scores[i], tp});
  }
  return out;
}

std::vector<RankedHit> match_junctions(const std::vector<Vec3>& pred, const std::vector<double>& scores,
                                       const std::vector<Vec3>& gt, double threshold, double min_score) {
  return greedy_nearest_match(scores, static_cast<int>(gt.size()), threshold, min_score,
                              [&](int i, int j) { return (pred[i] - gt[j]).norm(); });
}

double segment_pair_distance(const Vec3& p1, const Vec3& p2, const Vec3& g1, const Vec3& g2) {
  return std::min((p1 - g1).norm() + (p2 - g2).norm(), (p1 - g2).norm() + (p2 - g1).norm());
}

std::vector<RankedHit> match_edges(const ScoredWireframe& pred, const Wireframe& gt, double threshold,
                                   double min_score) {
  const auto& pj = pred.wireframe.junctions;
  const auto& pe = pred.wireframe.edges;
  return greedy_nearest_match(pred.edge_scores, static_cast<int>(gt.edges.size()), threshold, min_score,
                              [&](int i, int j) {
                                return segment_pair_distance(pj[pe[i][0]], pj[pe[i][1]], gt.junctions[gt.edges[j][0]],
                                                             gt.junctions[gt.edges[j][1]]);
                              });
}

double voc_average_precision(std::vector<RankedHit> hits, int64_t num_gt, ApTieRule ties) {
  if (num_gt <= 0 || hits.empty()) return 0.0;
  std::stable_sort(hits.begin(), hits.end(), [](const RankedHit& a, const RankedHit& b) { return a.score > b.score; });
  // Operating points (recall, precision) of the ranked list; with kGroupTies only after a group of equal scores.
  std::vector<double> rec{0.0}, prec{0.0};
  int64_t tp = 0;
  for (size_t k = 0; k < hits.size(); ++k) {
    tp += hits[k].true_positive ? 1 : 0;
    const bool group_end = k + 1 == hits.size() || hits[k + 1].score != hits[k].score;
    if (ties == ApTieRule::kListOrder || group_end) {
      rec.push_back(static_cast<double>(tp) / static_cast<double>(num_gt));
      prec.push_back(static_cast<double>(tp) / static_cast<double>(k + 1));
    }
  }
  rec.push_back(1.0);
  prec.push_back(0.0);
  for (size_t i = prec.size() - 1; i-- > 0;) prec[i] = std::max(prec[i], prec[i + 1]);
  double ap = 0.0;
  for (size_t i = 1; i < rec.size(); ++i)
    if (rec[i] != rec[i - 1]) ap += (rec[i] - rec[i - 1]) * prec[i];
  return ap;
}

ApSummary summarize_hits(const std::vector<RankedHit>& hits, int64_t num_gt, double threshold, ApTieRule ties) {
  ApSummary s;
  s.threshold = threshold;
  s.ground_truth = num_gt;
  s.predictions = static_cast<int64_t>(hits.size());
  s.true_positives = std::count_if(hits.begin(), hits.end(), [](const RankedHit& h) { return h.true_positive; });
  s.recall = num_gt > 0 ? static_cast<double>(s.true_positives) / static_cast<double>(num_gt) : 0.0;
  s.ap = voc_average_precision(hits, num_gt, ties);
  return s;
}

}  // namespace lc2wf
