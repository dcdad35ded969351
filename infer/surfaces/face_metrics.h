// Predicted faces scored against the faces of a ground-truth mesh (Roof-Image polyshape: roof / base / wall
// labels). A predicted face matches a GT face when their planes agree (normals within max_angle_deg, each
// polygon's centroid within max_distance_m of the other's plane) and their polygons overlap with
// IoU >= min_iou in the GT face's plane; matching is one-to-one, best IoU first.
#pragma once

#include <string>
#include <vector>

#include "infer/surfaces/surface_model.h"

namespace lc2wf {

struct FaceMatchOptions {
  double max_angle_deg = 10;
  double max_distance_m = 0.2;
  double min_iou = 0.5;
  double wall_tilt_deg = 15;  // GT faces labelled roof but within this of vertical (gable ends) count as walls
  void Check() const;         // throws std::invalid_argument naming the setting
};

// The GT mesh as surfaces: roof (label 1) -> roof, or wall when near-vertical (Roof-Image labels its vertical
// gable triangles roof; CityGML calls them walls); base (2) -> ground; wall (3) -> wall; a mesh without
// labels is labelled from its normals. Adjacent faces of one label in one plane (within 1 degree) are merged
// into one polygon, as the face finder merges its own.
SurfaceModel surfaces_from_mesh(const PolyMesh& mesh, double wall_tilt_deg = 15);

// Pairs (predicted face, GT face) matched one-to-one; `roof_only` restricts both sides to roof faces.
std::vector<std::pair<int, int>> match_faces(const SurfaceModel& pred, const SurfaceModel& gt, bool roof_only,
                                             const FaceMatchOptions& options);

struct FaceScores {  // one building
  int pred_roof = 0, gt_roof = 0, matched_roof = 0;  // roof facets and one-to-one roof matches
  int matched_faces = 0, label_agreements = 0;       // all faces matched regardless of label; of those, same label
  bool closed_solid = false;                         // the prediction's shell is a valid closed solid
  double pred_roof_area = 0, gt_roof_area = 0;       // m^2
};

FaceScores score_faces(const SurfaceModel& pred, const SurfaceModel& gt, const FaceMatchOptions& options = {});

}  // namespace lc2wf
