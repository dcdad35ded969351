// Windows and doors of a building's walls, laid out by storey: the storey height comes from each wall's
// own height (about `storey_height_m`, a whole number of storeys), so a shed and a tower both get rows of
// windows and every size scales with the storey. Shared by the photo textures (painted frames, sills,
// doors) and the photo scene (balconies below windows, paths from doors).
#pragma once

#include <cstdint>
#include <vector>

#include "tools/render/face_frames.h"

namespace lc2wf {

// A rectangle on a wall: u along the face's axis_u from its origin (metres), z world height.
struct FacadeRect {
  double u0 = 0, u1 = 0, z0 = 0, z1 = 0;
  bool contains(double u, double z) const { return u >= u0 && u <= u1 && z >= z0 && z <= z1; }
};

struct FacadeLayout {
  bool wall = false;            // only walls carry windows
  double storey_height = 0;     // metres, this wall's (its height over a whole number of storeys)
  int storeys = 0;
  double ground_z = 0;          // the building's ground
  double top_z = 0;             // eave height of this wall (the gutter hangs here)
  double peak_z = 0;            // its highest point (above top_z on gable ends, which have no gutter)
  std::vector<FacadeRect> windows;
  std::vector<int> window_storey;  // per window, 0 = ground floor
  std::vector<FacadeRect> doors;
};

struct FacadeOptions {
  double storey_height_m = 3.0;  // target; each wall rounds its height to whole storeys of about this
  bool windows = true;
  bool doors = true;
  void Check() const;
};

// One layout per face of `mesh` (frames from build_faced_mesh, same order). Every rectangle lies inside
// its face's polygon. Deterministic in `seed`.
std::vector<FacadeLayout> layout_facades(const PolyMesh& mesh, const std::vector<FaceFrame>& frames,
                                         const FacadeOptions& options, uint64_t seed);

}  // namespace lc2wf
