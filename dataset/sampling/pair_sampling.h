// Edge-stage pair labels and pair sampling (release section 3.2-3.4), distances in metres
// (release raw 7 -> 0.35 m false-positive distance). Which predicted junctions take part is decided by
// junction_selection.h, the rule inference uses too.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/selection/junction_selection.h"
#include "dataset/sampling/patches.h"

namespace lc2wf {

// The five pair classes.
enum PairClass : int { kPairIdentical = 0, kPairConnected = 1, kPairDistance2 = 2, kPairFarther = 3, kPairFalsePositive = 4 };

struct PairSamplingOptions {
  int pairs_per_building = 512;     // training: static + dynamic
  int max_static_pairs = 256;       // GT pairs kept (first ones, class order)
  double fp_distance_m = 0.35;      // a prediction farther than this from every GT junction is a false positive
  void Check() const;
};

// Nearest GT junction within fp_distance (strict <), else -1.
std::vector<int> assign_junction_labels(const std::vector<Vec3>& predicted, const std::vector<Vec3>& gt, double fp_distance_m);

// GT graph adjacency for pair classes.
class PairClassifier {
 public:
  explicit PairClassifier(const Wireframe& gt);
  // Class of a pair of (assigned) GT labels; -1 labels are false positives.
  int classify(int label_a, int label_b) const;

 private:
  int n_;
  std::vector<std::vector<char>> adj_;
};

// Training pairs: all GT pairs class-ordered (edges in the wireframe's edge order, then distance-2, then
// farther, each upper-triangle row-major), first max_static_pairs; then dynamic pairs of the selected
// junctions (select_junctions with SelectionCut::kTopK), all i<j combinations in confidence order, grouped
// by class 0,1,2,3,4, cut or cyclically repeated to fill pairs_per_building. With no dynamic pair the
// static pairs are repeated instead (the release would fail); a GT with fewer than 2 junctions gives an
// empty list. Dynamic pair indices i, j are positions in the selection.
std::vector<JunctionPair> sample_training_pairs(const Wireframe& gt, const JunctionSelection& selected,
                                                const PairSamplingOptions& options);

// The pairs the edge model classifies at inference and validation: every i<j pair of the selection in
// lexicographic order (indices = positions in the selection), with class labels when `gt` is given
// (otherwise -1). Fewer than 2 junctions: empty.
std::vector<JunctionPair> selection_pairs(const JunctionSelection& selected, const Wireframe* gt, double fp_distance_m);

}  // namespace lc2wf
