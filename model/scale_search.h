// The scale of a line cloud no evidence fixes (no GPS, known distance or building height): the networks are
// run on the cloud at several candidate building heights and the height whose wireframe they are most
// confident in wins. Heights are log-spaced over what buildings are (3-60 m), then refined around the best.
// The patch radius and input normalisation of the networks are metric, so a cloud at the wrong scale shows
// them corners and edges of the wrong size, and their confidence drops.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/inference.h"

namespace lc2wf {

// How confident the networks are in one candidate's wireframe (chosen by measurement: reconstruct/README.md,
// "Scale search").
enum class ScaleMeasure {
  kEdgeConfidence,      // mean over the kept edges of P(edge) x sqrt(c_i c_j)
  kEdgeEvidence,        // sum over the kept edges of P(edge) x c_i x c_j
  kConfidentJunctions,  // selected junctions with confidence > 0.5
  kJunctionMean,        // mean confidence of every junction candidate (one per sample point)
};
ScaleMeasure parse_scale_measure(const std::string& name);  // the names below; throws std::invalid_argument
std::string to_string(ScaleMeasure m);                       // edge-confidence, edge-evidence, confident-junctions, junction-mean

struct ScaleSearchOptions {
  double min_height_m = 3.0;
  double max_height_m = 60.0;
  int coarse_steps = 10;  // log-spaced heights from min to max
  int refine_rounds = 2;  // each tries the best height x step^(+-1/2), then x step^(+-1/4), ...
  ScaleMeasure measure = ScaleMeasure::kEdgeConfidence;  // the best of the four on the bench (reconstruct/README.md)
  void Check() const;  // throws std::invalid_argument naming the field
};

struct ScaleCandidate {
  double height_m = 0;
  double score = 0;  // the chosen measure
  double edge_confidence = 0, edge_evidence = 0, junction_mean = 0;
  int confident_junctions = 0, junctions = 0, edges = 0;
};

struct ScaleSearchResult {
  double height_m = 0;                 // the winner
  std::vector<ScaleCandidate> curve;   // every height tried, ascending
  double best_score = 0;
  double runner_up_score = 0;          // best score more than one coarse step away from the winner
  double runner_up_height_m = 0;
  LineCloud cloud;                     // the cloud at the winning height
  InferenceResult inference;           // and its wireframe
};

// The measures of one inference result.
ScaleCandidate measure_wireframe(const InferenceResult& r);
double score_of(const ScaleCandidate& c, ScaleMeasure m);

// `cloud_at(h)`: the cloud scaled so that its height above its ground is h metres (and whatever the caller
// does to a metric cloud before inference). Deterministic.
ScaleSearchResult search_scale(const WireframePredictor& predictor, const std::function<LineCloud(double height_m)>& cloud_at,
                               const PostProcessOptions& post, const ScaleSearchOptions& options = {});

}  // namespace lc2wf
