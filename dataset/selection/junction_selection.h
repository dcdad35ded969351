// The one rule that turns the junction model's candidates into the junctions that get paired, shared by
// the edge stage's training pairs, its validation and inference (as in the release): point NMS on
// the regressed positions, then a cut (c > min_confidence, or at training time the top_k without a cut),
// then refinement of the survivors against the cloud's segments.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/selection/corner_evidence.h"
#include "dataset/selection/footing_evidence.h"
#include "dataset/selection/junction_refine.h"
#include "dataset/selection/point_nms.h"
#include "dataset/sampling/sampling.h"

namespace lc2wf {

// Junction hypotheses of the junction model, one per sample point (metres).
struct PredictedJunctions {
  std::vector<Vec3> positions;
  std::vector<double> confidence;
  // How far each hypothesis was regressed from its patch's sample point (metres); empty when unknown
  // (predicted-junction files written before it was kept). Needed only for max_offset_m.
  std::vector<double> offset_m;
};

// The defaults are the sound selection, chosen on the validation split with the paper run's final models
// (experiments/README.md, "Choosing the junction selection"); release() is the paper's.
struct JunctionSelectionOptions {
  PointNmsRule nms = PointNmsRule::kGreedy;  // release: kSuppressor
  double nms_radius_m = 0.5;                 // release: 0.25 (5 raw)
  double min_confidence = 0.05;              // inference and validation keep c > this; release: 0.85
  int top_k = 100;                           // training keeps the top_k after NMS, whatever their confidence
  // Not in the release (infinity = every candidate): candidates regressed farther than this from their
  // sample point take no part. Trained on fragment clouds, a patch on an edge votes for a junction metres
  // away and its regression lands between the edge's two junctions: most false junctions are such votes.
  double max_offset_m = 0.75;
  // The max_offset_m a user's value asks for: <= 0 (flags and configs) means every candidate; NaN stays
  // NaN, for Check() to refuse.
  static double offset_limit(double metres) { return metres <= 0 ? std::numeric_limits<double>::infinity() : metres; }
  // Not in the release (one pass): the junction model runs on passes x its G sample points, G at a time
  // (the first G are the release's; farthest-point sampling goes on from them), so that junctions the
  // first G points leave uncovered get a patch too: with G = 256, 87 % of the GT junctions have a sample
  // point within 0.35 m, 97 % with 512 (experiments/README.md, "Sampling passes").
  int sampling_passes = 1;
  // Not in the release (a fixed 256 points): a large cloud gets more passes, one per this many metres of its
  // longer horizontal side (dataset/sampling/sampling.h, passes_for_extent); 0 = off. Every Roof-Image cloud
  // spans less than 40 m, so it changes nothing there; a 150 m block gets 4 passes (experiments/README.md,
  // "Large buildings: the sample budget").
  double metres_per_pass = 40.0;
  // Not in the release (one view): each candidate is the junction model's mean answer over this many views
  // of its patch, rotated by 90° steps or mirrored about the vertical axis (1, 2, 4 or 8; see
  // model/test_time_symmetry.h). Costs views x the junction model's time.
  int test_time_views = 1;
  // Not in the release (DensitySeedRule::release()): which endpoints seed the junction model's sample points
  // at inference. The model was trained on the release's seeds; seeding the small endpoint clusters too puts
  // more of its 256 patches where junctions are (experiments/README.md, "Density seeds").
  DensitySeedRule density_seeds = DensitySeedRule::loose();
  // The view counts there are (every one a group of turns and mirrors): 1, 2, 4 or 8.
  static bool valid_view_count(int64_t views) { return views == 1 || views == 2 || views == 4 || views == 8; }
  // Not in the release (its junctions stay where they were regressed): see junction_refine.h. The robust
  // scale was chosen on the validation split (experiments/README.md, "Robust junction refinement").
  JunctionRefineOptions refine{.radius = 0.5, .robust_scale = 0.05};
  // Not in the release (every junction is paired): after refinement a junction stays only where segments of
  // two directions end within corner.radius_m of it (corner_evidence.h; the radius was chosen on the
  // validation clouds, infer/README.md "Corner evidence").
  CornerEvidenceOptions corner{.radius_m = 0.3};
  // Not in the release (every junction is paired): a junction on the ground stays only where segment ends
  // stand over it within footing.radius_m (footing_evidence.h; infer/README.md "Footing evidence").
  FootingEvidenceOptions footing{.radius_m = 0.3};

  void Check() const;  // throws std::invalid_argument naming the bad field
  static JunctionSelectionOptions release();
};

// Which cut follows the NMS: inference and validation cut by confidence, training pair sampling keeps the
// top_k (the release's training pairs use no threshold).
enum class SelectionCut { kConfidence, kTopK };

struct JunctionSelection {
  std::vector<int> kept;            // indices into the candidates, descending confidence
  std::vector<Vec3> positions;      // the kept candidates (refined), same order
  std::vector<double> confidences;  // same order
  std::vector<std::string> notes;   // set when fewer than 2 junctions remain (nothing to pair)
};

// The offset screen select_junctions applies before the NMS: the indices of the candidates regressed at most
// max_offset_m from their sample point (all of them when it is infinite). Throws std::invalid_argument when a
// finite limit meets candidates without offsets.
std::vector<int> offset_screened(const PredictedJunctions& candidates, const JunctionSelectionOptions& options);

// Throws std::invalid_argument on mismatched sizes or non-finite candidates.
JunctionSelection select_junctions(const PredictedJunctions& candidates, const std::vector<Segment3>& segments,
                                   const JunctionSelectionOptions& options, SelectionCut cut = SelectionCut::kConfidence);

}  // namespace lc2wf
