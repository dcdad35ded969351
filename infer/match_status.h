// Which predicted and ground-truth elements the evaluator's matching rule pairs up, per threshold: the
// per-element view behind the pooled vAP/sAP counts, for showing matched / missed / spurious elements.
#pragma once

#include <cstdint>
#include <vector>

#include "model/scored_wireframe.h"

namespace lc2wf {

// Bit t of an entry is set when, at thresholds[t], the predicted element is a true positive (pred) or the
// GT element was hit by one (gt). Up to 8 thresholds.
struct MatchStatus {
  std::vector<uint8_t> pred;
  std::vector<uint8_t> gt;
};

// The rule of model/ap_metric.h (greedy, nearest GT only, descending score, ties by index; scores <=
// min_score are not predictions), applied to junctions and to edges.
MatchStatus junction_match_status(const ScoredWireframe& pred, const Wireframe& gt, const std::vector<double>& thresholds,
                                  double min_score);
MatchStatus edge_match_status(const ScoredWireframe& pred, const Wireframe& gt, const std::vector<double>& thresholds,
                              double min_score);

}  // namespace lc2wf
