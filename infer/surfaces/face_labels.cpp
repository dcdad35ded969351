#include "infer/surfaces/face_labels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "infer/surfaces/polygon_geometry.h"

namespace lc2wf {

void label_faces(SurfaceModel& m, double wall_tilt_deg, double level_distance) {
  const double wall_nz = std::sin(wall_tilt_deg * M_PI / 180);
  double lowest = std::numeric_limits<double>::infinity();
  for (const SurfaceFace& f : m.faces)
    for (int v : f.ring) lowest = std::min(lowest, m.vertices[v].z());
  const auto at_ground = [&](int v) { return m.vertices[v].z() <= lowest + level_distance; };
  bool walls_reach_ground = false;
  for (SurfaceFace& f : m.faces) {
    const Vec3 n = newell_normal(m.polygon(f)).normalized();
    f.label = std::abs(n.z()) <= wall_nz ? SurfaceLabel::kWall : SurfaceLabel::kRoof;
    if (f.label == SurfaceLabel::kWall && std::any_of(f.ring.begin(), f.ring.end(), at_ground)) walls_reach_ground = true;
  }
  // Without walls down to it, the lowest face is a roof (a roof-only wireframe), not the ground.
  if (!walls_reach_ground) return;
  for (SurfaceFace& f : m.faces)
    if (f.label == SurfaceLabel::kRoof && std::all_of(f.ring.begin(), f.ring.end(), at_ground) &&
        std::abs(newell_normal(m.polygon(f)).normalized().z()) >= std::cos(wall_tilt_deg * M_PI / 180))
      f.label = SurfaceLabel::kGround;
}

}  // namespace lc2wf
