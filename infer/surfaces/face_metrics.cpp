#include "infer/surfaces/face_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "infer/surfaces/face_labels.h"
#include "infer/surfaces/polygon_geometry.h"
#include "infer/surfaces/shell_assembly.h"

namespace lc2wf {
namespace {

struct FacePlane {
  Plane plane;
  Vec3 centroid;
};

FacePlane face_plane(const SurfaceModel& m, const SurfaceFace& f) {
  const std::vector<Vec3> pts = m.polygon(f);
  FacePlane fp;
  fp.plane.normal = newell_normal(pts).normalized();
  fp.centroid = Vec3::Zero();
  for (const Vec3& p : pts) fp.centroid += p;
  fp.centroid /= std::max<size_t>(1, pts.size());
  fp.plane.offset = fp.plane.normal.dot(fp.centroid);
  return fp;
}

double roof_area(const SurfaceModel& m) {
  double a = 0;
  for (const SurfaceFace& f : m.faces)
    if (f.label == SurfaceLabel::kRoof) a += polygon_area(m.polygon(f));
  return a;
}

}  // namespace

void FaceMatchOptions::Check() const {
  if (!(max_angle_deg > 0 && max_angle_deg < 90)) throw std::invalid_argument("faces.max_angle_deg must be in (0, 90)");
  if (!(max_distance_m > 0) || !std::isfinite(max_distance_m)) throw std::invalid_argument("faces.max_distance_m must be > 0");
  if (!(min_iou > 0 && min_iou <= 1)) throw std::invalid_argument("faces.min_iou must be in (0, 1]");
  if (!(wall_tilt_deg >= 0 && wall_tilt_deg < 90)) throw std::invalid_argument("faces.wall_tilt_deg must be in [0, 90)");
}

SurfaceModel surfaces_from_mesh(const PolyMesh& mesh, double wall_tilt_deg) {
  SurfaceModel m;
  m.vertices = mesh.vertices;
  const double wall_nz = std::sin(wall_tilt_deg * M_PI / 180);
  std::vector<SurfaceLabel> labels;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (mesh.faces[f].size() < 3) continue;
    SurfaceFace face{mesh.faces[f], SurfaceLabel::kRoof};
    if (f < mesh.labels.size()) {
      const FaceLabel l = mesh.labels[f];
      face.label = l == FaceLabel::Base ? SurfaceLabel::kGround : l == FaceLabel::Wall ? SurfaceLabel::kWall : SurfaceLabel::kRoof;
      if (face.label == SurfaceLabel::kRoof && std::abs(newell_normal(m.polygon(face)).normalized().z()) <= wall_nz)
        face.label = SurfaceLabel::kWall;
    }
    m.faces.push_back(std::move(face));
  }
  if (mesh.labels.empty()) label_faces(m, wall_tilt_deg, 0.05);  // GT vertices lie on their levels to the millimetre
  // Merge per label so a roof never absorbs a wall.
  std::vector<SurfaceFace> merged;
  for (SurfaceLabel label : {SurfaceLabel::kRoof, SurfaceLabel::kWall, SurfaceLabel::kGround}) {
    std::vector<CandidateFace> group;
    for (const SurfaceFace& f : m.faces)
      if (f.label == label) group.push_back({f.ring, 0});
    for (CandidateFace& c : merge_coplanar_faces(group, m.vertices, 1.0)) merged.push_back({std::move(c.ring), label});
  }
  m.faces = std::move(merged);
  m.status = m.faces.empty() ? ShellStatus::kNoFaces : ShellStatus::kOpenSurfaces;
  return m;
}

std::vector<std::pair<int, int>> match_faces(const SurfaceModel& pred, const SurfaceModel& gt, bool roof_only,
                                             const FaceMatchOptions& o) {
  o.Check();
  std::vector<std::tuple<double, int, int>> candidates;  // (-IoU, pred, gt)
  for (size_t g = 0; g < gt.faces.size(); ++g) {
    if (roof_only && gt.faces[g].label != SurfaceLabel::kRoof) continue;
    const FacePlane gp = face_plane(gt, gt.faces[g]);
    if (!gp.plane.normal.allFinite()) continue;
    const PlaneFrame frame = plane_frame(gp.plane.normal, gp.centroid);
    const std::vector<Vec2> gpoly = frame.to_2d(gt.polygon(gt.faces[g]));
    for (size_t p = 0; p < pred.faces.size(); ++p) {
      if (roof_only && pred.faces[p].label != SurfaceLabel::kRoof) continue;
      const FacePlane pp = face_plane(pred, pred.faces[p]);
      if (!pp.plane.normal.allFinite() || plane_angle_deg(pp.plane.normal, gp.plane.normal) > o.max_angle_deg) continue;
      if (std::abs(gp.plane.distance(pp.centroid)) > o.max_distance_m || std::abs(pp.plane.distance(gp.centroid)) > o.max_distance_m)
        continue;
      const double iou = polygon_iou(frame.to_2d(pred.polygon(pred.faces[p])), gpoly);
      if (iou >= o.min_iou) candidates.push_back({-iou, static_cast<int>(p), static_cast<int>(g)});
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> pred_used(pred.faces.size(), false), gt_used(gt.faces.size(), false);
  std::vector<std::pair<int, int>> out;
  for (const auto& [neg_iou, p, g] : candidates) {
    if (pred_used[p] || gt_used[g]) continue;
    pred_used[p] = gt_used[g] = true;
    out.push_back({p, g});
  }
  return out;
}

FaceScores score_faces(const SurfaceModel& pred, const SurfaceModel& gt, const FaceMatchOptions& o) {
  FaceScores s;
  s.pred_roof = pred.count(SurfaceLabel::kRoof);
  s.gt_roof = gt.count(SurfaceLabel::kRoof);
  s.matched_roof = static_cast<int>(match_faces(pred, gt, true, o).size());
  for (const auto& [p, g] : match_faces(pred, gt, false, o)) {
    ++s.matched_faces;
    if (pred.faces[p].label == gt.faces[g].label) ++s.label_agreements;
  }
  s.closed_solid = pred.closed_solid();
  s.pred_roof_area = roof_area(pred);
  s.gt_roof_area = roof_area(gt);
  return s;
}

}  // namespace lc2wf
