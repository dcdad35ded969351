#include "infer/surfaces/surface_model.h"

#include <algorithm>

namespace lc2wf {

const char* to_string(SurfaceLabel label) {
  switch (label) {
    case SurfaceLabel::kRoof: return "roof";
    case SurfaceLabel::kWall: return "wall";
    case SurfaceLabel::kGround: return "ground";
  }
  return "roof";
}

const char* to_string(ShellStatus status) {
  switch (status) {
    case ShellStatus::kClosedSolid: return "closed_solid";
    case ShellStatus::kOpenSurfaces: return "open_surfaces";
    case ShellStatus::kNoFaces: return "no_faces";
  }
  return "no_faces";
}

std::vector<Vec3> SurfaceModel::polygon(const SurfaceFace& face) const {
  std::vector<Vec3> out;
  out.reserve(face.ring.size());
  for (int v : face.ring) out.push_back(vertices[v]);
  return out;
}

int SurfaceModel::count(SurfaceLabel label) const {
  return static_cast<int>(std::count_if(faces.begin(), faces.end(), [&](const SurfaceFace& f) { return f.label == label; }));
}

}  // namespace lc2wf
