#include "dataset/geometry/roof_kind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace lc2wf {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct FacePlane {
  Vec3 normal;  // unit, pointing up (z >= 0)
  double offset;
  double area;
  double mean_z;
};

// Newell's normal: robust for non-convex and slightly non-planar polygons; its length is twice the area.
bool face_plane(const PolyMesh& mesh, const std::vector<int>& face, FacePlane& out) {
  if (face.size() < 3) return false;
  Vec3 n = Vec3::Zero(), centroid = Vec3::Zero();
  for (size_t i = 0; i < face.size(); ++i) {
    const Vec3& a = mesh.vertices[face[i]];
    const Vec3& b = mesh.vertices[face[(i + 1) % face.size()]];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
    centroid += a;
  }
  centroid /= static_cast<double>(face.size());
  const double len = n.norm();
  if (!(len > 1e-12)) return false;
  n /= len;
  if (n.z() < 0) n = -n;
  out = {n, n.dot(centroid), 0.5 * len, centroid.z()};
  return true;
}

}  // namespace

void RoofKindOptions::Check() const {
  if (!(flat_tilt_deg > 0 && flat_tilt_deg < 90)) throw std::invalid_argument("flat_tilt_deg must be in (0, 90)");
  if (!(flat_share_mixed >= 0 && flat_share_mixed < flat_share_flat && flat_share_flat <= 1))
    throw std::invalid_argument("flat_share_mixed < flat_share_flat <= 1 is required");
  if (!(level_tol_m > 0)) throw std::invalid_argument("level_tol_m must be > 0");
  if (!(plane_angle_tol_deg > 0) || !(plane_offset_tol_m > 0))
    throw std::invalid_argument("plane_angle_tol_deg and plane_offset_tol_m must be > 0");
}

RoofKind classify_roof(const PolyMesh& mesh, const RoofKindOptions& options) {
  options.Check();
  const bool labelled = mesh.labels.size() == mesh.faces.size();
  const double cos_flat = std::cos(options.flat_tilt_deg * kPi / 180.0);
  const double cos_plane = std::cos(options.plane_angle_tol_deg * kPi / 180.0);
  std::vector<FacePlane> flat, pitched;
  double flat_area = 0, pitched_area = 0;
  double eaves_z = 1e300;                // lowest vertex of a pitched roof face
  std::vector<double> vertical_tops;     // top of each wall (and vertical roof face)
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    FacePlane p;
    if (!face_plane(mesh, mesh.faces[f], p)) continue;
    const bool roof = labelled ? mesh.labels[f] == FaceLabel::Roof : p.normal.z() > std::sin(10.0 * kPi / 180.0);
    if (p.normal.z() < 0.1 && (roof || !labelled || mesh.labels[f] == FaceLabel::Wall)) {
      double top = -1e300;
      for (int v : mesh.faces[f]) top = std::max(top, mesh.vertices[v].z());
      vertical_tops.push_back(top);
      continue;
    }
    if (!roof) continue;
    if (p.normal.z() >= cos_flat) {
      flat.push_back(p);
      flat_area += p.area;
    } else {
      pitched.push_back(p);
      pitched_area += p.area;
      for (int v : mesh.faces[f]) eaves_z = std::min(eaves_z, mesh.vertices[v].z());
    }
  }
  const double total = flat_area + pitched_area;
  if (!(total > 0)) return RoofKind::Unknown;
  const double flat_share = flat_area / total;
  if (flat_share >= options.flat_share_flat) {
    std::vector<double> levels;
    for (const FacePlane& p : flat) levels.push_back(p.mean_z);
    std::sort(levels.begin(), levels.end());
    int count = 1;
    for (size_t i = 1; i < levels.size(); ++i)
      if (levels[i] - levels[i - 1] > options.level_tol_m) ++count;
    return count == 1 ? RoofKind::Flat : RoofKind::FlatMulti;
  }
  if (flat_share > options.flat_share_mixed) return RoofKind::Mixed;
  // Distinct pitched planes, largest first so small faces join the plane they belong to.
  std::sort(pitched.begin(), pitched.end(), [](const FacePlane& a, const FacePlane& b) { return a.area > b.area; });
  std::vector<FacePlane> planes;
  for (const FacePlane& p : pitched) {
    const bool known = std::any_of(planes.begin(), planes.end(), [&](const FacePlane& q) {
      return p.normal.dot(q.normal) >= cos_plane && std::abs(p.offset - q.offset) <= options.plane_offset_tol_m;
    });
    if (!known) planes.push_back(p);
  }
  // A gable end: a wall (or vertical roof face) that rises above the pitched roof's lowest point.
  const bool gable = std::any_of(vertical_tops.begin(), vertical_tops.end(),
                                 [&](double top) { return top > eaves_z + options.level_tol_m; });
  if (planes.size() == 1) return RoofKind::Shed;
  if (planes.size() == 2) return RoofKind::Gabled;
  if (planes.size() <= 4) return gable ? RoofKind::Gabled : RoofKind::Hipped;
  return RoofKind::Complex;
}

std::string roof_kind_name(RoofKind kind) {
  switch (kind) {
    case RoofKind::Flat: return "flat";
    case RoofKind::FlatMulti: return "flat-multi";
    case RoofKind::Shed: return "shed";
    case RoofKind::Gabled: return "gabled";
    case RoofKind::Hipped: return "hipped";
    case RoofKind::Mixed: return "mixed";
    case RoofKind::Complex: return "complex";
    case RoofKind::Unknown: return "unknown";
  }
  return "unknown";
}

}  // namespace lc2wf
