// A building's boundary surfaces as planar polygons with roof / wall / ground semantics: what
// surfaces_from_wireframe() builds, what the CityJSON and OBJ writers write and what the face metrics score.
// Coordinates are metres in the frame of the wireframe they come from.
#pragma once

#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

enum class SurfaceLabel { kRoof, kWall, kGround };
const char* to_string(SurfaceLabel label);  // "roof", "wall", "ground"

struct SurfaceFace {
  std::vector<int> ring;  // vertex ids, counter-clockwise seen from outside when the shell is oriented
  SurfaceLabel label = SurfaceLabel::kRoof;
};

// Why a shell is not a valid closed solid; an empty list means it is one.
enum class ShellStatus {
  kClosedSolid,   // every edge bounds two faces, consistently oriented, planar, no self-intersection
  kOpenSurfaces,  // faces found, but the evidence does not close them into a valid solid (see reasons)
  kNoFaces,       // no planar cycle bounds a face
};
const char* to_string(ShellStatus status);  // "closed_solid", "open_surfaces", "no_faces"

struct SurfaceModel {
  std::vector<Vec3> vertices;
  std::vector<SurfaceFace> faces;
  ShellStatus status = ShellStatus::kNoFaces;
  std::vector<std::string> reasons;  // human-readable, one per problem found (empty for a closed solid)
  long work_steps = 0;               // steps of the search charged to SurfaceOptions::max_work_steps (work_budget.h)

  bool closed_solid() const { return status == ShellStatus::kClosedSolid; }
  std::vector<Vec3> polygon(const SurfaceFace& face) const;
  int count(SurfaceLabel label) const;
};

}  // namespace lc2wf
