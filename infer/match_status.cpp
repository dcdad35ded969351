#include "infer/match_status.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "model/ap_metric.h"

namespace lc2wf {
namespace {

MatchStatus match_status(const std::vector<double>& scores, int num_gt, const std::vector<double>& thresholds,
                         double min_score, const std::function<double(int, int)>& distance) {
  if (thresholds.size() > 8) throw std::invalid_argument("match status: at most 8 thresholds");
  MatchStatus s;
  s.pred.assign(scores.size(), 0);
  s.gt.assign(num_gt, 0);
  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(scores.size()); ++i)
    if (scores[i] > min_score) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });
  // The nearest GT element and its distance do not depend on the threshold: compute them once.
  std::vector<int> nearest(scores.size(), -1);
  std::vector<double> best(scores.size(), std::numeric_limits<double>::infinity());
  for (int i : order)
    for (int j = 0; j < num_gt; ++j) {
      const double d = distance(i, j);
      if (d < best[i]) best[i] = d, nearest[i] = j;
    }
  for (size_t t = 0; t < thresholds.size(); ++t) {
    const uint8_t bit = static_cast<uint8_t>(1u << t);
    for (int i : order) {
      const int j = nearest[i];
      if (j < 0 || !(best[i] < thresholds[t]) || (s.gt[j] & bit)) continue;
      s.gt[j] |= bit;
      s.pred[i] |= bit;
    }
  }
  return s;
}

}  // namespace

MatchStatus junction_match_status(const ScoredWireframe& pred, const Wireframe& gt, const std::vector<double>& thresholds,
                                  double min_score) {
  const auto& pj = pred.wireframe.junctions;
  return match_status(pred.junction_scores, static_cast<int>(gt.junctions.size()), thresholds, min_score,
                      [&](int i, int j) { return (pj[i] - gt.junctions[j]).norm(); });
}

MatchStatus edge_match_status(const ScoredWireframe& pred, const Wireframe& gt, const std::vector<double>& thresholds,
                              double min_score) {
  const auto& pj = pred.wireframe.junctions;
  const auto& pe = pred.wireframe.edges;
  return match_status(pred.edge_scores, static_cast<int>(gt.edges.size()), thresholds, min_score, [&](int i, int j) {
    return segment_pair_distance(pj[pe[i][0]], pj[pe[i][1]], gt.junctions[gt.edges[j][0]], gt.junctions[gt.edges[j][1]]);
  });
}

}  // namespace lc2wf
