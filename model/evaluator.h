// Whole-split evaluation: vAP/vRecall, sAP/sRecall (pooled over buildings) and WED (mean over buildings),
// the numbers of the paper's Table 2. Feed buildings one by one with add(), then read report().
#pragma once

#include <string>
#include <vector>

#include "model/ap_metric.h"
#include "model/scored_wireframe.h"
#include "model/wed_metric.h"

namespace lc2wf {

struct EvalOptions {
  std::vector<double> vertex_thresholds{0.15, 0.25, 0.35};  // η for vAP, metres (release: 3/5/7 raw)
  std::vector<double> edge_thresholds{0.25, 0.35, 0.50};    // η for sAP, metres (release: 5/7/10 raw)
  double min_score = 0.0;                // predictions scoring <= this are dropped (release: 0)
  ApTieRule ties = ApTieRule::kListOrder;  // equal scores: building order, then prediction order (release)
  double raw_per_metre = kRawUnitsPerMetre;          // dataset scale, used only by the release WED's sqrt(raw) move cost
  bool strict_wed = false;               // also compute the strict WED variant

  void Check() const;  // throws std::invalid_argument naming the bad field
};

struct BuildingEval {
  std::string name;
  bool prediction_missing = false;  // no prediction file: evaluated as an empty wireframe
  int gt_vertices = 0;
  int gt_edges = 0;
  int pred_vertices = 0;  // junctions referenced by at least one edge
  int pred_edges = 0;
  std::vector<int> vertex_tp;  // per vertex threshold
  std::vector<int> edge_tp;    // per edge threshold
  WedResult wed;
  WedResult wed_strict;  // all zero unless options.strict_wed
};

// Mean of each WED term over buildings.
struct WedMean {
  double add_vertex = 0, del_vertex = 0, add_edge = 0, del_edge = 0, total_num = 0;
  double move = 0, add_edge_length = 0, del_edge_length = 0, total_dist = 0;
};

struct EvalReport {
  EvalOptions options;
  std::vector<ApSummary> vertex;  // one per vertex threshold
  std::vector<ApSummary> edge;    // one per edge threshold
  double vertex_ap_mean = 0, vertex_recall_mean = 0, edge_ap_mean = 0, edge_recall_mean = 0;  // "avg." columns
  WedMean wed;
  WedMean wed_strict;
  std::vector<BuildingEval> buildings;  // in add() order

  std::vector<std::string> missing_predictions() const;
};

class Evaluator {
 public:
  explicit Evaluator(EvalOptions options);

  // Scores one building. Isolated predicted junctions are ignored (the paper's predictions are the
  // junctions of the final edges). Throws std::invalid_argument (naming `name`) on inconsistent input.
  const BuildingEval& add(const std::string& name, const ScoredWireframe& pred, const Wireframe& gt,
                          bool prediction_missing = false);
  EvalReport report() const;
  size_t size() const { return buildings_.size(); }

 private:
  EvalOptions options_;
  std::vector<std::vector<RankedHit>> vertex_hits_;  // pooled, per threshold
  std::vector<std::vector<RankedHit>> edge_hits_;
  int64_t gt_vertices_ = 0;
  int64_t gt_edges_ = 0;
  std::vector<BuildingEval> buildings_;
};

}  // namespace lc2wf
