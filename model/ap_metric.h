// Ranked average precision of junctions (vAP) and edges (sAP) as the LC2WF release computes them
// (its evaluation script): per building, predictions in score order are matched greedily to their
// *nearest* ground-truth element only; the (score, TP) flags of all buildings are pooled into one list
// and scored with VOC all-point AP against the total ground-truth count.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "model/scored_wireframe.h"

namespace lc2wf {

struct RankedHit {
  double score = 0.0;
  bool true_positive = false;
};

// How equal scores are ranked in the pooled list. kListOrder (lc2wf-eval's default) ranks ties in the
// order hits were added: building order, then each building's prediction order, the order in which the
// release builds its pooled arrays. kGroupTies evaluates precision/recall only after a whole group of
// equal scores (an order-free threshold sweep).
enum class ApTieRule { kGroupTies, kListOrder };

struct ApSummary {
  double threshold = 0.0;  // metres
  double ap = 0.0;         // in [0, 1]; 0 when there is no ground truth at all
  double recall = 0.0;     // true positives / ground truth (micro over buildings)
  int64_t true_positives = 0;
  int64_t predictions = 0;
  int64_t ground_truth = 0;
};

// Greedy nearest-only matching (release rule): predictions with score <= min_score are ignored; the rest,
// in descending score order (ties: lower index first), are TP iff distance(i, nearest GT j) < threshold
// and j was not hit before. The nearest GT is the first index reaching the minimum distance.
std::vector<RankedHit> greedy_nearest_match(const std::vector<double>& scores, int num_gt, double threshold,
                                            double min_score, const std::function<double(int, int)>& distance);

// vAP matching: Euclidean distance between junctions.
std::vector<RankedHit> match_junctions(const std::vector<Vec3>& pred, const std::vector<double>& scores,
                                       const std::vector<Vec3>& gt, double threshold, double min_score = 0.0);

// Distance between two segments: sum of endpoint distances under the better of the two orientations.
double segment_pair_distance(const Vec3& p1, const Vec3& p2, const Vec3& g1, const Vec3& g2);

// sAP matching: edges compared with segment_pair_distance.
std::vector<RankedHit> match_edges(const ScoredWireframe& pred, const Wireframe& gt, double threshold,
                                   double min_score = 0.0);

// VOC all-point AP of a pooled hit list against num_gt ground-truth elements.
double voc_average_precision(std::vector<RankedHit> hits, int64_t num_gt, ApTieRule ties);

// AP + recall + counts of a pooled hit list.
ApSummary summarize_hits(const std::vector<RankedHit>& hits, int64_t num_gt, double threshold, ApTieRule ties);

}  // namespace lc2wf
