// The faces section of lc2wf-eval's outputs: per-building face scores pooled into roof-facet precision and
// recall, labelling accuracy, the share of valid closed solids and the roof-area error, as Markdown and JSON.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "infer/surfaces/face_metrics.h"
#include "infer/surfaces/surface_options.h"

namespace lc2wf {

struct FaceBuilding {
  std::string name;
  FaceScores scores;
  std::string status;              // the predicted shell's status (to_string(ShellStatus))
  std::vector<std::string> reasons;
  double seconds = 0;              // surfaces_from_wireframe on this prediction
};

struct FaceReport {
  bool gt_has_faces = true;        // false: the GT is a line cloud's wireframe, only the shells are checked
  FaceMatchOptions options;
  std::vector<FaceBuilding> buildings;
};

struct FaceSummary {
  int buildings = 0, closed_solids = 0;
  int pred_roof = 0, gt_roof = 0, matched_roof = 0, matched_faces = 0, label_agreements = 0;
  double roof_precision = 0, roof_recall = 0, label_accuracy = 0, closed_share = 0;
  double roof_area_error = 0;        // mean over buildings with GT roof area of |pred - GT| / GT
  double roof_area_error_m2 = 0;     // the same, absolute
  double mean_ms = 0, max_ms = 0;    // surfaces_from_wireframe per building
};
FaceSummary summarize_faces(const FaceReport& report);

// One building for the report: the surfaces of `prediction` (timed; returned in `surfaces` when given), checked,
// and scored against the faces of `gt_mesh` when it has any.
// `edge_scores`: the prediction's edge probabilities (one per edge) or empty (surfaces_from_wireframe.h).
FaceBuilding evaluate_faces(const std::string& name, const Wireframe& prediction, const std::vector<double>& edge_scores,
                            const PolyMesh& gt_mesh, SurfaceModel* surfaces = nullptr,
                            const SurfaceOptions& surface_options = {}, const FaceMatchOptions& match_options = {});

std::string faces_markdown(const FaceReport& report, const std::string& method);
nlohmann::json faces_json(const FaceReport& report);

}  // namespace lc2wf
