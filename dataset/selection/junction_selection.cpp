#include "dataset/selection/junction_selection.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace lc2wf {

void JunctionSelectionOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("JunctionSelectionOptions." + what); };
  if (!(nms_radius_m > 0) || !std::isfinite(nms_radius_m)) fail("nms_radius_m must be a positive distance in metres");
  if (!(max_offset_m > 0)) fail("max_offset_m must be a positive distance in metres (infinity: no limit)");
  if (!(min_confidence >= 0 && min_confidence <= 1)) fail("min_confidence must be in [0, 1]");
  if (top_k < 2) fail("top_k must be >= 2");
  if (sampling_passes < 1 || sampling_passes > 8) fail("sampling_passes must be in [1, 8]");
  if (!(metres_per_pass >= 0) || !std::isfinite(metres_per_pass)) fail("metres_per_pass must be >= 0 (0: off)");
  if (!valid_view_count(test_time_views)) fail("test_time_views must be 1, 2, 4 or 8");
  density_seeds.Check();
  refine.Check();
  corner.Check();
  footing.Check();
}

JunctionSelectionOptions JunctionSelectionOptions::release() {
  JunctionSelectionOptions o;
  o.nms = PointNmsRule::kSuppressor;
  o.nms_radius_m = 0.25;  // 5 raw
  o.min_confidence = 0.85;
  o.max_offset_m = std::numeric_limits<double>::infinity();
  o.sampling_passes = 1;
  o.metres_per_pass = 0;
  o.test_time_views = 1;
  o.density_seeds = DensitySeedRule::release();
  o.refine.radius = 0.0;
  o.corner.radius_m = 0.0;
  o.footing.radius_m = 0.0;
  return o;
}

std::vector<int> offset_screened(const PredictedJunctions& c, const JunctionSelectionOptions& o) {
  std::vector<int> eligible;
  const bool limited = std::isfinite(o.max_offset_m);
  if (limited && c.offset_m.size() != c.positions.size())
    throw std::invalid_argument("select_junctions: max_offset_m needs each candidate's offset, but " +
                                std::to_string(c.offset_m.size()) + " offsets came with " +
                                std::to_string(c.positions.size()) + " candidates (predict the junctions again)");
  for (size_t k = 0; k < c.positions.size(); ++k)
    if (!limited || c.offset_m[k] <= o.max_offset_m) eligible.push_back(static_cast<int>(k));
  return eligible;
}

JunctionSelection select_junctions(const PredictedJunctions& c, const std::vector<Segment3>& segments,
                                   const JunctionSelectionOptions& o, SelectionCut cut) {
  o.Check();
  if (c.positions.size() != c.confidence.size())
    throw std::invalid_argument("select_junctions: " + std::to_string(c.positions.size()) + " candidates but " +
                                std::to_string(c.confidence.size()) + " confidences");
  for (size_t k = 0; k < c.positions.size(); ++k)
    if (!c.positions[k].allFinite() || !std::isfinite(c.confidence[k]))
      throw std::invalid_argument("select_junctions: candidate " + std::to_string(k) + " has a non-finite value");
  const std::vector<int> eligible = offset_screened(c, o);
  std::vector<Vec3> positions;
  std::vector<double> confidence;
  for (int k : eligible) positions.push_back(c.positions[k]), confidence.push_back(c.confidence[k]);
  JunctionSelection s;
  for (int e : point_nms(positions, confidence, o.nms_radius_m, o.nms)) {
    const int k = eligible[static_cast<size_t>(e)];
    if (cut == SelectionCut::kConfidence ? c.confidence[k] <= o.min_confidence : static_cast<int>(s.kept.size()) >= o.top_k)
      continue;
    s.kept.push_back(k);
    s.positions.push_back(c.positions[k]);
    s.confidences.push_back(c.confidence[k]);
  }
  s.positions = refine_junctions(s.positions, segments, o.refine);
  // The cloud's evidence for each refined junction: lines of two directions end there, and on the ground the
  // building stands over it.
  auto keep_where = [&s](const std::vector<char>& shown) {
    size_t n = 0;
    for (size_t j = 0; j < shown.size(); ++j)
      if (shown[j]) s.kept[n] = s.kept[j], s.positions[n] = s.positions[j], s.confidences[n] = s.confidences[j], ++n;
    s.kept.resize(n), s.positions.resize(n), s.confidences.resize(n);
  };
  if (o.corner.enabled()) keep_where(corner_evidence(s.positions, segments, o.corner));
  if (o.footing.enabled()) keep_where(footing_evidence(s.positions, segments, o.footing));
  if (c.positions.empty()) s.notes.push_back("no junction candidates");
  if (s.kept.size() < 2) {
    const std::string cut_text =
        cut == SelectionCut::kConfidence ? "with confidence > " + std::to_string(o.min_confidence) + " " : "";
    s.notes.push_back(std::to_string(s.kept.size()) + " junction(s) " + cut_text + "after NMS" +
                      (o.corner.enabled() ? " and the corner check" : "") +
                      (o.footing.enabled() ? " and the footing check" : "") + ": no pair to connect");
  }
  return s;
}

}  // namespace lc2wf
