#include "dataset/pair_sampling.h"

#include <array>
#include <stdexcept>

#include "dataset/point_nms.h"

namespace lc2wf {

void PairSamplingOptions::Check() const {
  if (pairs_per_building < 1) throw std::invalid_argument("PairSamplingOptions.pairs_per_building must be >= 1");
  if (max_static_pairs < 0 || max_static_pairs > pairs_per_building) {
    throw std::invalid_argument("PairSamplingOptions.max_static_pairs must be in [0, pairs_per_building]");
  }
  if (top_k < 2) throw std::invalid_argument("PairSamplingOptions.top_k must be >= 2");
  if (!(nms_radius_m >= 0)) throw std::invalid_argument("PairSamplingOptions.nms_radius_m must be >= 0");
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

namespace {

// All i<j pairs of `points` grouped by class, each group in combination order.
std::vector<JunctionPair> class_ordered_pairs(const std::vector<Vec3>& points, const std::vector<int>& ids,
                                              const std::vector<int>* labels, const PairClassifier* cls) {
  std::array<std::vector<JunctionPair>, 5> groups;
  std::vector<JunctionPair> unlabelled;
  for (size_t a = 0; a < points.size(); ++a) {
    for (size_t b = a + 1; b < points.size(); ++b) {
      JunctionPair p{points[a], points[b], ids[a], ids[b], -1, false};
      if (cls) {
        p.label = cls->classify((*labels)[a], (*labels)[b]);
        groups[p.label].push_back(p);
      } else {
        unlabelled.push_back(p);
      }
    }
  }
  if (!cls) return unlabelled;
  std::vector<JunctionPair> out;
  for (const auto& g : groups) out.insert(out.end(), g.begin(), g.end());
  return out;
}

std::vector<int> nms_kept(const PredictedJunctions& pred, double radius) {
  if (pred.positions.size() != pred.confidence.size()) throw std::invalid_argument("PredictedJunctions: positions and confidences differ in size");
  return suppressor_nms(pred.positions, pred.confidence, radius);
}

}  // namespace

std::vector<JunctionPair> sample_training_pairs(const Wireframe& gt, const PredictedJunctions& pred, const PairSamplingOptions& o) {
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

  std::vector<int> kept = nms_kept(pred, o.nms_radius_m);
  if (static_cast<int>(kept.size()) > o.top_k) kept.resize(o.top_k);
  std::vector<Vec3> pts;
  for (int k : kept) pts.push_back(pred.positions[k]);
  const std::vector<int> labels = assign_junction_labels(pts, gt.junctions, o.fp_distance_m);
  std::vector<JunctionPair> dyn = class_ordered_pairs(pts, kept, &labels, &cls);
  const std::vector<JunctionPair> pool = dyn.empty() ? out : dyn;
  if (pool.empty()) return out;
  for (size_t k = 0; k < need; ++k) out.push_back(pool[k % pool.size()]);
  return out;
}

std::vector<JunctionPair> sample_test_pairs(const PredictedJunctions& pred, const Wireframe* gt, const PairSamplingOptions& o,
                                            std::vector<int>* kept_out) {
  o.Check();
  std::vector<int> kept;
  for (int k : nms_kept(pred, o.nms_radius_m)) {
    if (pred.confidence[k] > o.test_confidence) kept.push_back(k);
  }
  if (kept_out) *kept_out = kept;
  if (kept.size() < 2) return {};
  std::vector<Vec3> pts;
  for (int k : kept) pts.push_back(pred.positions[k]);
  if (!gt) return class_ordered_pairs(pts, kept, nullptr, nullptr);
  const PairClassifier cls(*gt);
  const std::vector<int> labels = assign_junction_labels(pts, gt->junctions, o.fp_distance_m);
  return class_ordered_pairs(pts, kept, &labels, &cls);
}

}  // namespace lc2wf
