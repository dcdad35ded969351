#include "infer/surfaces/face_metrics_io.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/util/number_format.h"
#include "infer/surfaces/wireframe_surfaces.h"

namespace lc2wf {
namespace {

double ratio(double a, double b) { return b > 0 ? a / b : 0; }
std::string pct(double v) { return format_number("%.1f", 100 * v); }

}  // namespace

FaceSummary summarize_faces(const FaceReport& r) {
  FaceSummary s;
  int with_area = 0;
  for (const FaceBuilding& b : r.buildings) {
    const FaceScores& x = b.scores;
    ++s.buildings;
    s.closed_solids += x.closed_solid ? 1 : 0;
    s.pred_roof += x.pred_roof;
    s.gt_roof += x.gt_roof;
    s.matched_roof += x.matched_roof;
    s.matched_faces += x.matched_faces;
    s.label_agreements += x.label_agreements;
    if (x.gt_roof_area > 0) {
      ++with_area;
      s.roof_area_error += std::abs(x.pred_roof_area - x.gt_roof_area) / x.gt_roof_area;
      s.roof_area_error_m2 += std::abs(x.pred_roof_area - x.gt_roof_area);
    }
    s.mean_ms += 1000 * b.seconds;
    s.max_ms = std::max(s.max_ms, 1000 * b.seconds);
  }
  s.roof_precision = ratio(s.matched_roof, s.pred_roof);
  s.roof_recall = ratio(s.matched_roof, s.gt_roof);
  s.label_accuracy = ratio(s.label_agreements, s.matched_faces);
  s.closed_share = ratio(s.closed_solids, s.buildings);
  s.roof_area_error = ratio(s.roof_area_error, with_area);
  s.roof_area_error_m2 = ratio(s.roof_area_error_m2, with_area);
  s.mean_ms = ratio(s.mean_ms, s.buildings);
  return s;
}

FaceBuilding evaluate_faces(const std::string& name, const Wireframe& prediction, const std::vector<double>& edge_scores,
                            const PolyMesh& gt_mesh, SurfaceModel* surfaces, const SurfaceOptions& surface_options,
                            const FaceMatchOptions& match_options) {
  FaceBuilding b;
  b.name = name;
  const auto t0 = std::chrono::steady_clock::now();
  SurfaceModel m = edge_scores.empty() ? surfaces_from_wireframe(prediction, surface_options)
                                        : surfaces_from_wireframe(prediction, edge_scores, surface_options);
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  b.status = to_string(m.status);
  b.reasons = m.reasons;
  b.scores = gt_mesh.faces.empty() ? FaceScores{} : score_faces(m, surfaces_from_mesh(gt_mesh, match_options.wall_tilt_deg), match_options);
  b.scores.closed_solid = m.closed_solid();
  if (surfaces) *surfaces = std::move(m);
  return b;
}

std::string faces_markdown(const FaceReport& r, const std::string& method) {
  const FaceSummary s = summarize_faces(r);
  std::string md = "\n## (d) Faces: LoD2 surfaces from the predicted wireframes\n\n";
  if (!r.gt_has_faces) {
    md += "| method | valid closed solids |\n|---|---|\n| " + method + " | " + pct(s.closed_share) + " % (" +
          std::to_string(s.closed_solids) + " of " + std::to_string(s.buildings) + ") |\n\n" +
          "Face scores not computed: the ground truth is a line cloud's wireframe, which has no faces (give --gt with "
          "the meshes to score them).\n";
    return md;
  }
  md += "| method | roof P | roof R | labels | valid closed solids | roof area error |\n|---|---|---|---|---|---|\n";
  md += "| " + method + " | " + pct(s.roof_precision) + " | " + pct(s.roof_recall) + " | " + pct(s.label_accuracy) + " | " +
        pct(s.closed_share) + " % (" + std::to_string(s.closed_solids) + " of " + std::to_string(s.buildings) + ") | " +
        pct(s.roof_area_error) + " % (" + format_number("%.1f", s.roof_area_error_m2) + " m²) |\n\n";
  md += "Roof facets: " + std::to_string(s.matched_roof) + " matched of " + std::to_string(s.pred_roof) + " predicted and " +
        std::to_string(s.gt_roof) + " in the GT meshes; a predicted facet matches a GT facet (one-to-one, best overlap first) when "
        "their planes agree within " + format_number("%g", r.options.max_angle_deg) + "° and " +
        format_number("%g", r.options.max_distance_m) + " m and their polygons overlap with IoU ≥ " +
        format_number("%g", r.options.min_iou) + " in the GT facet's plane. Labels: roof / wall / ground agreement over the " +
        std::to_string(s.matched_faces) + " faces matched regardless of label (GT gable ends labelled roof but vertical count as "
        "walls). Valid closed solid: planar, closed, consistently oriented, no self-intersection. Roof area error: mean over "
        "buildings of |predicted − GT| / GT roof area. Faces found in " + format_number("%.2f", s.mean_ms) + " ms per building (max " +
        format_number("%.1f", s.max_ms) + ").\n";
  return md;
}

nlohmann::json faces_json(const FaceReport& r) {
  const FaceSummary s = summarize_faces(r);
  nlohmann::json j = {{"gt_has_faces", r.gt_has_faces},
                      {"buildings", s.buildings},
                      {"closed_solids", s.closed_solids},
                      {"closed_share", s.closed_share},
                      {"surfaces_ms_mean", s.mean_ms},
                      {"surfaces_ms_max", s.max_ms}};
  if (r.gt_has_faces) {
    j["match"] = {{"max_angle_deg", r.options.max_angle_deg}, {"max_distance_m", r.options.max_distance_m}, {"min_iou", r.options.min_iou}};
    j["roof_precision"] = s.roof_precision;
    j["roof_recall"] = s.roof_recall;
    j["label_accuracy"] = s.label_accuracy;
    j["roof_area_error"] = s.roof_area_error;
    j["roof_area_error_m2"] = s.roof_area_error_m2;
    j["totals"] = {{"pred_roof", s.pred_roof}, {"gt_roof", s.gt_roof}, {"matched_roof", s.matched_roof},
                   {"matched_faces", s.matched_faces}, {"label_agreements", s.label_agreements}};
  }
  j["per_building"] = nlohmann::json::array();
  for (const FaceBuilding& b : r.buildings) {
    nlohmann::json x = {{"name", b.name}, {"status", b.status}, {"reasons", b.reasons}, {"ms", 1000 * b.seconds}};
    if (r.gt_has_faces) {
      const FaceScores& c = b.scores;
      x["pred_roof"] = c.pred_roof, x["gt_roof"] = c.gt_roof, x["matched_roof"] = c.matched_roof;
      x["matched_faces"] = c.matched_faces, x["label_agreements"] = c.label_agreements;
      x["pred_roof_area_m2"] = c.pred_roof_area, x["gt_roof_area_m2"] = c.gt_roof_area;
    }
    j["per_building"].push_back(std::move(x));
  }
  return j;
}

}  // namespace lc2wf
