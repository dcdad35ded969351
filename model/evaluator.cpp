#include "model/evaluator.h"

#include <cmath>
#include <stdexcept>

namespace lc2wf {
namespace {

void check_thresholds(const std::vector<double>& t, const std::string& field) {
  if (t.empty()) throw std::invalid_argument("EvalOptions." + field + " is empty");
  for (double v : t)
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument("EvalOptions." + field + " must hold positive finite distances (metres), got " +
                                  std::to_string(v));
}

WedMean mean_of(const std::vector<BuildingEval>& buildings, bool strict) {
  WedMean m;
  if (buildings.empty()) return m;
  for (const auto& b : buildings) {
    const WedResult& w = strict ? b.wed_strict : b.wed;
    m.add_vertex += w.add_vertex;
    m.del_vertex += w.del_vertex;
    m.add_edge += w.add_edge;
    m.del_edge += w.del_edge;
    m.total_num += w.total_num();
    m.move += w.move;
    m.add_edge_length += w.add_edge_length;
    m.del_edge_length += w.del_edge_length;
    m.total_dist += w.total_dist();
  }
  const double n = static_cast<double>(buildings.size());
  for (double* v : {&m.add_vertex, &m.del_vertex, &m.add_edge, &m.del_edge, &m.total_num, &m.move,
                    &m.add_edge_length, &m.del_edge_length, &m.total_dist})
    *v /= n;
  return m;
}

double mean(const std::vector<ApSummary>& s, double ApSummary::*field) {
  double sum = 0;
  for (const auto& x : s) sum += x.*field;
  return s.empty() ? 0.0 : sum / static_cast<double>(s.size());
}

int count_tp(const std::vector<RankedHit>& hits) {
  int n = 0;
  for (const auto& h : hits) n += h.true_positive ? 1 : 0;
  return n;
}

}  // namespace

void EvalOptions::Check() const {
  check_thresholds(vertex_thresholds, "vertex_thresholds");
  check_thresholds(edge_thresholds, "edge_thresholds");
  if (!std::isfinite(min_score)) throw std::invalid_argument("EvalOptions.min_score must be finite");
  if (!(raw_per_metre > 0.0) || !std::isfinite(raw_per_metre))
    throw std::invalid_argument("EvalOptions.raw_per_metre must be positive, got " + std::to_string(raw_per_metre));
}

std::vector<std::string> EvalReport::missing_predictions() const {
  std::vector<std::string> names;
  for (const auto& b : buildings)
    if (b.prediction_missing) names.push_back(b.name);
  return names;
}

Evaluator::Evaluator(EvalOptions options) : options_(std::move(options)) {
  options_.Check();
  vertex_hits_.resize(options_.vertex_thresholds.size());
  edge_hits_.resize(options_.edge_thresholds.size());
}

const BuildingEval& Evaluator::add(const std::string& name, const ScoredWireframe& pred_in, const Wireframe& gt,
                                   bool prediction_missing) {
  pred_in.check("prediction of " + name);
  ScoredWireframe::with_unit_scores(gt).check("ground truth of " + name);
  const ScoredWireframe pred = referenced_junctions_only(pred_in);

  BuildingEval b;
  b.name = name;
  b.prediction_missing = prediction_missing;
  b.gt_vertices = static_cast<int>(gt.junctions.size());
  b.gt_edges = static_cast<int>(gt.edges.size());
  b.pred_vertices = static_cast<int>(pred.wireframe.junctions.size());
  b.pred_edges = static_cast<int>(pred.wireframe.edges.size());
  for (size_t t = 0; t < options_.vertex_thresholds.size(); ++t) {
    auto hits = match_junctions(pred.wireframe.junctions, pred.junction_scores, gt.junctions,
                                options_.vertex_thresholds[t], options_.min_score);
    b.vertex_tp.push_back(count_tp(hits));
    vertex_hits_[t].insert(vertex_hits_[t].end(), hits.begin(), hits.end());
  }
  for (size_t t = 0; t < options_.edge_thresholds.size(); ++t) {
    auto hits = match_edges(pred, gt, options_.edge_thresholds[t], options_.min_score);
    b.edge_tp.push_back(count_tp(hits));
    edge_hits_[t].insert(edge_hits_[t].end(), hits.begin(), hits.end());
  }
  b.wed = wed_release(pred.wireframe, gt, options_.raw_per_metre);
  if (options_.strict_wed) b.wed_strict = wed_strict(pred.wireframe, gt);
  gt_vertices_ += b.gt_vertices;
  gt_edges_ += b.gt_edges;
  buildings_.push_back(std::move(b));
  return buildings_.back();
}

EvalReport Evaluator::report() const {
  EvalReport r;
  r.options = options_;
  for (size_t t = 0; t < options_.vertex_thresholds.size(); ++t)
    r.vertex.push_back(summarize_hits(vertex_hits_[t], gt_vertices_, options_.vertex_thresholds[t], options_.ties));
  for (size_t t = 0; t < options_.edge_thresholds.size(); ++t)
    r.edge.push_back(summarize_hits(edge_hits_[t], gt_edges_, options_.edge_thresholds[t], options_.ties));
  r.vertex_ap_mean = mean(r.vertex, &ApSummary::ap);
  r.vertex_recall_mean = mean(r.vertex, &ApSummary::recall);
  r.edge_ap_mean = mean(r.edge, &ApSummary::ap);
  r.edge_recall_mean = mean(r.edge, &ApSummary::recall);
  r.wed = mean_of(buildings_, false);
  if (options_.strict_wed) r.wed_strict = mean_of(buildings_, true);
  r.buildings = buildings_;
  return r;
}

}  // namespace lc2wf
