#include "model/scale_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace lc2wf {

namespace {
const std::pair<ScaleMeasure, const char*> kNames[] = {{ScaleMeasure::kEdgeConfidence, "edge-confidence"},
                                                       {ScaleMeasure::kEdgeEvidence, "edge-evidence"},
                                                       {ScaleMeasure::kConfidentJunctions, "confident-junctions"},
                                                       {ScaleMeasure::kJunctionMean, "junction-mean"}};
}  // namespace

ScaleMeasure parse_scale_measure(const std::string& name) {
  for (const auto& [m, n] : kNames)
    if (name == n) return m;
  throw std::invalid_argument("unknown scale measure '" + name + "' (edge-confidence, edge-evidence, confident-junctions, junction-mean)");
}

std::string to_string(ScaleMeasure m) {
  for (const auto& [k, n] : kNames)
    if (k == m) return n;
  return "?";
}

void ScaleSearchOptions::Check() const {
  if (!(min_height_m > 0 && std::isfinite(min_height_m))) throw std::invalid_argument("ScaleSearchOptions.min_height_m must be > 0");
  if (!(max_height_m > min_height_m && std::isfinite(max_height_m))) throw std::invalid_argument("ScaleSearchOptions.max_height_m must be > min_height_m");
  if (coarse_steps < 2 || coarse_steps > 100) throw std::invalid_argument("ScaleSearchOptions.coarse_steps must be in [2, 100]");
  if (refine_rounds < 0 || refine_rounds > 10) throw std::invalid_argument("ScaleSearchOptions.refine_rounds must be in [0, 10]");
}

ScaleCandidate measure_wireframe(const InferenceResult& r) {
  ScaleCandidate c;
  const ScoredWireframe& w = r.wireframe;
  c.junctions = static_cast<int>(w.wireframe.junctions.size());
  c.edges = static_cast<int>(w.wireframe.edges.size());
  for (size_t e = 0; e < w.wireframe.edges.size(); ++e) {
    const auto& [i, j] = w.wireframe.edges[e];
    const double ci = w.junction_scores[i], cj = w.junction_scores[j];
    c.edge_evidence += w.edge_scores[e] * ci * cj;
    c.edge_confidence += w.edge_scores[e] * std::sqrt(ci * cj);
  }
  if (c.edges > 0) c.edge_confidence /= c.edges;
  for (double conf : r.selection.confidences) c.confident_junctions += conf > 0.5;
  for (double conf : r.junctions.confidence) c.junction_mean += conf;
  if (!r.junctions.confidence.empty()) c.junction_mean /= static_cast<double>(r.junctions.confidence.size());
  return c;
}

double score_of(const ScaleCandidate& c, ScaleMeasure m) {
  switch (m) {
    case ScaleMeasure::kEdgeConfidence: return c.edge_confidence;
    case ScaleMeasure::kEdgeEvidence: return c.edge_evidence;
    case ScaleMeasure::kConfidentJunctions: return c.confident_junctions;
    case ScaleMeasure::kJunctionMean: return c.junction_mean;
  }
  return 0;
}

ScaleSearchResult search_scale(const WireframePredictor& predictor, const std::function<LineCloud(double height_m)>& cloud_at,
                               const PostProcessOptions& post, const ScaleSearchOptions& o) {
  o.Check();
  post.Check();
  ScaleSearchResult result;
  std::map<double, ScaleCandidate> tried;
  bool have_best = false;
  auto try_height = [&](double h) {
    h = std::clamp(h, o.min_height_m, o.max_height_m);  // refinement never leaves the range
    if (tried.count(h)) return;
    LineCloud cloud = cloud_at(h);
    InferenceResult r = predictor.predict(cloud, post);
    ScaleCandidate c = measure_wireframe(r);
    c.height_m = h;
    c.score = score_of(c, o.measure);
    tried[h] = c;
    // Ties keep the earlier (lower) height: deterministic whatever the order of the tries.
    if (!have_best || c.score > result.best_score || (c.score == result.best_score && h < result.height_m)) {
      have_best = true;
      result.height_m = h, result.best_score = c.score;
      result.cloud = std::move(cloud), result.inference = std::move(r);
    }
  };
  const double step = std::log(o.max_height_m / o.min_height_m) / (o.coarse_steps - 1);  // log units
  for (int k = 0; k < o.coarse_steps; ++k) try_height(k + 1 == o.coarse_steps ? o.max_height_m : o.min_height_m * std::exp(k * step));
  double delta = step;
  for (int round = 0; round < o.refine_rounds; ++round) {
    delta /= 2;
    const double centre = result.height_m;
    try_height(centre * std::exp(-delta));
    try_height(centre * std::exp(delta));
  }
  for (const auto& [h, c] : tried) {
    result.curve.push_back(c);
    if (std::abs(std::log(h / result.height_m)) > step * 1.01 && c.score >= result.runner_up_score && result.runner_up_height_m == 0)
      result.runner_up_score = c.score, result.runner_up_height_m = h;
    else if (std::abs(std::log(h / result.height_m)) > step * 1.01 && c.score > result.runner_up_score)
      result.runner_up_score = c.score, result.runner_up_height_m = h;
  }
  return result;
}

}  // namespace lc2wf
