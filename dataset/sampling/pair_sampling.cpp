#include "dataset/sampling/pair_sampling.h"

#include <algorithm>
#include <memory>
#include <stdexcept>


namespace lc2wf {

void PairSamplingOptions::Check() const {
  if (pairs_per_building < 1) throw std::invalid_argument("PairSamplingOptions.pairs_per_building must be >= 1");
  if (max_static_pairs < 0 || max_static_pairs > pairs_per_building) {
    throw std::invalid_argument("PairSamplingOptions.max_static_pairs must be in [0, pairs_per_building]");
  }
  if (!(fp_distance_m > 0)) throw std::invalid_argument("PairSamplingOptions.fp_distance_m must be > 0");
}

std::vector<int> assign_junction_labels(const std::vector<Vec3>& pred, const std::vector<Vec3>& gt, double fp) {
  std::vector<int> out(pred.size(), -1);
  for (size_t i = 0; i < pred.size(); ++i) {
    double best = fp * fp;
    for (size_t j = 0; j < gt.size(); ++j) {
      const double d2 = (pred[i] - gt[j]).squaredNorm();
      if (d2 < best) {
        best = d2;
        out[i] = static_cast<int>(j);
      }
    }
  }
  return out;
}

PairClassifier::PairClassifier(const Wireframe& gt)
    : n_(static_cast<int>(gt.junctions.size())), adj_(n_, std::vector<char>(n_, 0)) {
  for (const auto& e : gt.edges) {
    if (e[0] < 0 || e[1] < 0 || e[0] >= n_ || e[1] >= n_) throw std::out_of_range("PairClassifier: GT edge id out of range");
    adj_[e[0]][e[1]] = adj_[e[1]][e[0]] = 1;
  }
}

int PairClassifier::classify(int a, int b) const {
  if (a < 0 || b < 0) return kPairFalsePositive;
  if (a >= n_ || b >= n_) throw std::out_of_range("PairClassifier: label out of range");
  if (a == b) return kPairIdentical;
  if (adj_[a][b]) return kPairConnected;
  for (int k = 0; k < n_; ++k) {
    if (adj_[a][k] && adj_[k][b]) return kPairDistance2;
  }
  return kPairFarther;
}

std::vector<JunctionPair> sample_training_pairs(const Wireframe& gt, const JunctionSelection& selected,
                                                const PairSamplingOptions& o) {
  o.Check();
  const int V = static_cast<int>(gt.junctions.size());
  if (V < 2) return {};
  const PairClassifier cls(gt);
  // Static GT pairs: edges first (in the wireframe's order), then distance 2, then farther.
  std::vector<JunctionPair> out;
  for (const auto& e : gt.edges) out.push_back({gt.junctions[e[0]], gt.junctions[e[1]], e[0], e[1], kPairConnected, true});
  for (int want : {kPairDistance2, kPairFarther}) {
    for (int a = 0; a < V; ++a) {
      for (int b = a + 1; b < V; ++b) {
        if (cls.classify(a, b) == want) out.push_back({gt.junctions[a], gt.junctions[b], a, b, want, true});
      }
    }
  }
  if (static_cast<int>(out.size()) > o.max_static_pairs) out.resize(o.max_static_pairs);
  const size_t need = static_cast<size_t>(o.pairs_per_building) - out.size();

  // Grouped by class (a stable sort keeps combination order within a class), as the release orders them.
  std::vector<JunctionPair> dyn = selection_pairs(selected, &gt, o.fp_distance_m);
  std::stable_sort(dyn.begin(), dyn.end(), [](const JunctionPair& a, const JunctionPair& b) { return a.label < b.label; });
  const std::vector<JunctionPair> pool = dyn.empty() ? out : dyn;
  if (pool.empty()) return out;
  for (size_t k = 0; k < need; ++k) out.push_back(pool[k % pool.size()]);
  return out;
}

std::vector<JunctionPair> selection_pairs(const JunctionSelection& selected, const Wireframe* gt, double fp_distance_m) {
  const std::vector<Vec3>& points = selected.positions;
  std::vector<JunctionPair> out;
  if (points.size() < 2) return out;
  std::vector<int> labels;
  std::unique_ptr<PairClassifier> cls;
  if (gt) {
    labels = assign_junction_labels(points, gt->junctions, fp_distance_m);
    cls = std::make_unique<PairClassifier>(*gt);
  }
  out.reserve(points.size() * (points.size() - 1) / 2);
  for (int a = 0; a < static_cast<int>(points.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(points.size()); ++b)
      out.push_back({points[a], points[b], a, b, cls ? cls->classify(labels[a], labels[b]) : -1, false});
  return out;
}

}  // namespace lc2wf
